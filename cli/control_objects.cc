#include "cli/control_objects.h"

#include <optional>
#include <string>

#include "base/result.h"
#include "cli/json_fields.h"
#include "cli/printable.h"

namespace radfarm {
namespace {

// The master's strings are printed on a terminal: control characters come escaped
// (cli/printable.h).
std::optional<std::string> PrintableOrNull(const std::optional<std::string>& text) {
  if (!text) return std::nullopt;
  return Printable(*text);
}

// The optional "timeline" array: {phase, where, wall_seconds, cpu_seconds} each.
Status ParseTimeline(const nlohmann::json& object, const std::string& where,
                     JobTimeline* timeline) {
  const auto it = object.find("timeline");
  if (it == object.end() || it->is_null()) return Ok{};
  if (!it->is_array()) return Error{"'" + where + ".timeline' is not an array"};
  std::vector<std::string_view> phases;
  for (JobPhase phase : kJobPhases) phases.push_back(JobPhaseName(phase));
  for (size_t i = 0; i < it->size(); ++i) {
    FieldReader r((*it)[i], where + ".timeline[" + std::to_string(i) + "]");
    const std::optional<JobPhase> phase = JobPhaseNamed(r.OneOf("phase", phases));
    const std::string place = r.OneOf("where", {kRanOnMaster, kRanOnAgents, kRanOnClient});
    const double wall = r.Number("wall_seconds");
    const double cpu = r.Number("cpu_seconds");
    RADFARM_RETURN_IF_ERROR(r.status());
    AddToTimeline(timeline, *phase, place, wall, cpu);
  }
  return Ok{};
}

}  // namespace

bool IsTerminalState(std::string_view state) {
  return state == "done" || state == "failed" || state == "cancelled";
}

Result<JobInfo> ParseJob(const nlohmann::json& object, const std::string& where) {
  FieldReader r(object, where);
  JobInfo job;
  job.id = r.Int("id");
  job.name = Printable(r.String("name"));
  job.state =
      r.OneOf("state", {"queued", "running", "paused", "held", "done", "failed", "cancelled"});
  job.priority = r.Int("priority");
  job.seed = r.Count("seed");
  job.scene_hash = Printable(r.String("scene_hash"));
  job.patches = r.Count("patches");
  job.submitted_at_ms = r.NullableInt("submitted_at_ms");
  job.started_at_ms = r.NullableInt("started_at_ms");
  job.finished_at_ms = r.NullableInt("finished_at_ms");
  job.error = PrintableOrNull(r.NullableString("error"));
  job.round = r.Count("round");
  job.rays = r.Count("rays");
  job.unshot_fraction = r.Number("unshot_fraction");
  job.tolerance = r.Number("tolerance");
  job.progress = r.Number("progress");
  job.rays_per_second = r.Number("rays_per_second");
  job.agents = r.Count("agents");
  job.eta_seconds = r.NullableNumber("eta_seconds");
  job.stop_reason = PrintableOrNull(r.NullableString("stop_reason"));
  job.waiting_for_agents = r.Bool("waiting_for_agents");
  job.phase = PrintableOrNull(r.NullableString("phase"));
  job.direct_start = PrintableOrNull(r.NullableString("direct_start"));
  job.display = PrintableOrNull(r.NullableString("display"));
  RADFARM_RETURN_IF_ERROR(r.status());
  RADFARM_RETURN_IF_ERROR(ParseTimeline(object, where, &job.timeline));
  return job;
}

Result<AgentInfo> ParseAgent(const nlohmann::json& object, const std::string& where) {
  FieldReader r(object, where);
  AgentInfo agent;
  agent.id = r.Int("id");
  agent.name = Printable(r.String("name"));
  agent.address = Printable(r.String("address"));
  agent.threads = r.Count("threads");
  agent.rays_per_second = r.Number("rays_per_second");
  agent.load = r.Number("load");
  agent.leases = r.Count("leases");
  agent.connected_ms = r.Int("connected_ms");
  agent.last_heartbeat_ms_ago = r.Int("last_heartbeat_ms_ago");
  agent.results = r.Count("results");
  RADFARM_RETURN_IF_ERROR(r.status());
  return agent;
}

Result<EventInfo> ParseEvent(const nlohmann::json& object, const std::string& where) {
  FieldReader r(object, where);
  EventInfo event;
  event.time_ms = r.Int("time_ms");
  event.level = r.OneOf("level", {"info", "warning", "error"});
  event.job = r.NullableInt("job");
  event.text = Printable(r.String("text"));
  RADFARM_RETURN_IF_ERROR(r.status());
  return event;
}

}  // namespace radfarm
