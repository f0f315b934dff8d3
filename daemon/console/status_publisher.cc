#include "daemon/console/status_publisher.h"

#include <chrono>
#include <vector>

#include "daemon/console/farm_metrics.h"
#include "daemon/console/web/metrics_text.h"
#include "daemon/jobs/clock.h"
#include "store/job_store.h"

namespace radfarm::daemon {
namespace {

using nlohmann::json;

int64_t UnixMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

json EventsJson(const std::vector<store::Event>& events) {
  json list = json::array();
  for (const store::Event& e : events) {
    list.push_back({{"time_ms", e.time_ms},
                    {"level", std::string(store::EventLevelName(e.level))},
                    {"job", e.job ? json(*e.job) : json(nullptr)},
                    {"text", e.text}});
  }
  return list;
}

}  // namespace

StatusPublisher::StatusPublisher(loop::EventLoop& loop, ControlRequests& control, JobRounds& jobs,
                                 StoreThread& store, web::StatusBoard& board)
    : loop_(loop), control_(control), jobs_(jobs), store_(store), board_(board) {}

void StatusPublisher::Start() {
  timer_ = std::make_unique<loop::Timer>(loop_);
  Refresh();
}

void StatusPublisher::Stop() {
  stopped_ = true;
  if (timer_) timer_->Close();
}

void StatusPublisher::Refresh() {
  if (stopped_) return;
  ControlRequest list;
  list.command = ControlCommand::kList;
  control_.Handle(list, [this](ControlResponse jobs) {
    if (stopped_) return;
    ControlRequest agents_request;
    agents_request.command = ControlCommand::kAgents;
    // Agents are answered at once, from memory.
    control_.Handle(agents_request, [this, jobs = std::move(jobs)](ControlResponse agents) {
      if (stopped_) return;
      store_.Run([](store::JobStore& s) { return s.ListRecentEvents(kEvents); },
                 [this, jobs, agents](Result<std::vector<store::Event>> events) {
                   if (stopped_) return;
                   const bool ok = jobs.body.value("ok", false) && agents.body.value("ok", false) &&
                                   events.ok();
                   if (ok) Publish(jobs.body["jobs"], agents.body["agents"], EventsJson(*events));
                   timer_->Start(kInterval, [this] { Refresh(); });
                 });
    });
  });
}

void StatusPublisher::Publish(const json& jobs, const json& agents, const json& events) {
  web::StatusSnapshot snapshot;
  snapshot.status_json =
      json{{"time_ms", UnixMs()}, {"jobs", jobs}, {"agents", agents}, {"events", events}}.dump(
          -1, ' ', false, json::error_handler_t::replace);  // never throw on bad UTF-8
  web::FarmMetrics metrics = FarmMetricsOf(jobs, agents, jobs_.batch_totals(LoopClock(loop_).Now()),
                                           jobs_.checkpoint_latency(), store_.queued());
  metrics.round_results_kept = jobs_.journal().results_written;
  metrics.round_result_writes = jobs_.journal().writes;
  metrics.batches_restored = jobs_.batches_restored();
  metrics.gather_ahead_batches = jobs_.gather_ahead_adopted();
  snapshot.metrics_text = web::FormatMetrics(metrics);
  board_.Publish(std::move(snapshot));
}

}  // namespace radfarm::daemon
