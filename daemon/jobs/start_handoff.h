// StartHandoff: a job's direct-light start (core/direct_start.h), handed from the compute thread,
// where its solver is being built (RunningJob::Prepare, or a refinement restart in Reduce), to the
// loop thread, which leases its patches to the agents (job_start.cc); and their values handed back.
//
// The compute thread waits in Await: the solver cannot be built without its start, and nothing
// else of the job can happen meanwhile; the loop goes on serving agents and clients. The loop
// collects new requests on its tick (Take) and answers each once: the values, nullopt (no agent
// takes start work: the compute thread traces it itself), or an error (the job was cancelled or
// paused, or the master stops: the compute work then ends with that error).
//
// Threads: Await on any thread but the loop's; Take, Answer and AbandonAll on the loop thread.
// `wake` runs under the handoff's lock in Await, never after AbandonAll: its owner may close what
// it wakes once AbandonAll has returned.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/result.h"
#include "display/point_work.h"
#include "protocol/scene_packing.h"
#include "store/job_store.h"

namespace radfarm::daemon {

struct StartRequest {
  store::JobId job = 0;
  PointWork work;  // start work over every patch of the context's scene
  std::shared_ptr<const protocol::PackedScene> context;
  bool sky = false;  // the scene has a sky: for agents of protocol::kSkyVersion alone
};

using StartAnswer = Result<std::optional<PointValues>>;

class StartHandoff {
 public:
  // `wake` tells the loop thread a request waits (loop::Async::Send).
  explicit StartHandoff(std::function<void()> wake) : wake_(std::move(wake)) {}

  // Compute thread: hands `request` over and waits for its answer.
  StartAnswer Await(StartRequest request);

  // Loop thread: the requests handed over since the last call, each with its ticket.
  std::vector<std::pair<uint64_t, StartRequest>> Take();
  // Loop thread: answers the request of `ticket` (once; a ticket already answered is ignored).
  void Answer(uint64_t ticket, StartAnswer answer);
  // Loop thread: answers every open request, and every later one, with an error: the master stops.
  void AbandonAll(const std::string& why);

 private:
  const std::function<void()> wake_;
  std::mutex mutex_;
  std::condition_variable answered_;
  uint64_t next_ticket_ = 1;
  std::deque<std::pair<uint64_t, StartRequest>> waiting_;  // handed over, not yet taken
  std::map<uint64_t, std::optional<StartAnswer>> open_;    // taken or waiting, by ticket
  std::optional<std::string> abandoned_;
};

}  // namespace radfarm::daemon
