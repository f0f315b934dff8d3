// PreviewCache: the status page's job previews, drawn once per checkpoint and shared. A preview
// costs the whole solution read and the scene meshed again, and any client that can read the page
// can ask for one as often as it likes. So:
//
//  - a preview is keyed by its job's latest checkpoint (PreviewKey) and kept once drawn, until a
//    newer checkpoint of the job is asked for (at most kMaxKept jobs' previews, least recently
//    asked for dropped first);
//  - concurrent requests for one key share one computation (a PreviewFlight);
//  - a request that leaves (its answer taken, or its client gone) says so (Leave); when the last
//    requester of an unfinished flight leaves, the flight is cancelled and forgotten: its work
//    stops at its next step (PreviewFlight::cancelled) and a later request starts afresh.
//
// Flight lifecycle: Join (new: the joiner computes it) --Finish(png)--> kept (an error is not kept)
//                   Join (new) --every joiner Left--> cancelled, forgotten
//
// Threads: every method on any thread (one mutex); a flight's Wait on its requester's thread.
#pragma once

#include <chrono>
#include <compare>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "base/result.h"
#include "base/unique_fd.h"

namespace radfarm::daemon {

// The checkpoint a preview is drawn from: its job, round and the time it was written (a job sent
// back by a failed verification writes a round again).
struct PreviewKey {
  int64_t job = 0;
  uint32_t round = 0;
  int64_t written_ms = 0;
  auto operator<=>(const PreviewKey&) const = default;
};

// One computation of one key, shared by its requesters.
class PreviewFlight {
 public:
  PreviewFlight();
  PreviewFlight(const PreviewFlight&) = delete;
  PreviewFlight& operator=(const PreviewFlight&) = delete;

  // Whether every requester has gone: the work should stop.
  bool cancelled() const;
  bool finished() const;
  // Waits until the flight finishes (its PNG or error), the client on `client_fd` closes its end
  // (-1: no client to watch), or `timeout` passes; nullopt for the last two.
  std::optional<Result<std::string>> Wait(int client_fd, std::chrono::milliseconds timeout) const;

 private:
  friend class PreviewCache;
  void Wake();  // makes done_ readable for every waiter

  mutable std::mutex mutex_;
  std::optional<Result<std::string>> png_;
  int requesters_ = 0;
  bool cancelled_ = false;
  UniqueFd done_;  // an eventfd, readable once the flight finished
  PreviewKey key_;
};

class PreviewCache {
 public:
  static constexpr size_t kMaxKept = 16;

  struct Joined {
    std::shared_ptr<PreviewFlight> flight;
    bool compute = false;  // a new flight: the caller starts its work and calls Finish
  };
  // A requester of `key` arrives: it joins the finished or running flight, or a new one.
  Joined Join(const PreviewKey& key);
  // The requester has its answer or its client has gone. The last requester of an unfinished
  // flight cancels it.
  void Leave(const std::shared_ptr<PreviewFlight>& flight);
  // The computation's end: waiters wake; a PNG is kept for later requests, an error is not. Once
  // a flight has finished (or Close ended it), later Finishes are ignored.
  void Finish(const std::shared_ptr<PreviewFlight>& flight, Result<std::string> png);
  // Shutdown: every unfinished flight ends with `why` (its waiters wake: the HTTP threads must
  // not wait for drawings the stopping preview thread will not finish), and nothing is kept.
  void Close(const std::string& why);

  // Previews drawn, flights cancelled, requests answered from a kept or running flight.
  uint64_t drawn() const;
  uint64_t cancelled() const;
  uint64_t shared() const;

 private:
  void Forget(const PreviewFlight* flight);  // mutex_ held

  mutable std::mutex mutex_;
  std::map<PreviewKey, std::shared_ptr<PreviewFlight>> flights_;
  std::list<PreviewKey> recent_;  // kept flights' keys, most recently asked for first
  uint64_t drawn_ = 0, cancelled_ = 0, shared_ = 0;
};

}  // namespace radfarm::daemon
