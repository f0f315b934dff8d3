// StatusPublisher: makes the web console's status snapshots on the loop thread and publishes
// them on the StatusBoard the HTTP threads read (daemon/console/web/status_board.h).
//
// A refresh asks ControlRequests for what `radfarm list --json` and `radfarm agents --json`
// show (the same code, so the page and the CLI never disagree), reads the recent events on the
// store thread, adds the master's counters for /metrics, and publishes. The next refresh starts
// kInterval after the last one was published, so a slow store slows the page rather than piling
// up store work.
//
// Loop thread only. Stop() before the master drains its store: answers still on their way are
// dropped, and the object must live until they have come back (the master keeps it to the end).
#pragma once

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>

#include "base/result.h"
#include "daemon/console/web/status_board.h"
#include "daemon/control/control_requests.h"
#include "daemon/jobs/job_rounds.h"
#include "daemon/jobs/store_thread.h"
#include "loop/event_loop.h"
#include "loop/timer.h"

namespace radfarm::daemon {

class StatusPublisher {
 public:
  static constexpr std::chrono::milliseconds kInterval{500};
  static constexpr int kEvents = 30;  // recent events shown

  StatusPublisher(loop::EventLoop& loop, ControlRequests& control, JobRounds& jobs,
                  StoreThread& store, web::StatusBoard& board);
  StatusPublisher(const StatusPublisher&) = delete;
  StatusPublisher& operator=(const StatusPublisher&) = delete;

  // Starts the first refresh now.
  void Start();
  void Stop();

 private:
  void Refresh();
  void Publish(const nlohmann::json& jobs, const nlohmann::json& agents,
               const nlohmann::json& events);

  loop::EventLoop& loop_;
  ControlRequests& control_;
  JobRounds& jobs_;
  StoreThread& store_;
  web::StatusBoard& board_;
  std::unique_ptr<loop::Timer> timer_;
  bool stopped_ = false;
};

}  // namespace radfarm::daemon
