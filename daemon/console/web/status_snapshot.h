// StatusSnapshot: what the web console serves (docs/OPERATIONS.md, "The status page"). The loop
// thread makes one, publishes it on a StatusBoard and never touches it again, so the HTTP threads
// read it without a lock on the master's state.
#pragma once

#include <cstdint>
#include <string>

namespace radfarm::web {

struct StatusSnapshot {
  uint64_t version = 0;  // set by StatusBoard::Publish: 1, 2, ...
  // {"time_ms", "jobs", "agents", "events"}: the job, agent and event objects of the control
  // socket (docs/CONTROL.md), one line of JSON (GET /api/status, and each server-sent event).
  std::string status_json;
  std::string metrics_text;  // the Prometheus text exposition (GET /metrics)
};

}  // namespace radfarm::web
