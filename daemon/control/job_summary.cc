#include "daemon/control/job_summary.h"

#include <nlohmann/json.hpp>

#include "base/result.h"
#include "core/solve_control.h"

namespace radfarm::daemon {

std::string SubmittedSettings::ToJson() const {
  // The scene path is any bytes; a byte that is not UTF-8 becomes U+FFFD (it is only shown).
  return nlohmann::json{{"tolerance", tolerance},     {"max_rays", max_rays},
                        {"max_seconds", max_seconds}, {"sampler", sampler},
                        {"patches", patches},         {"scene", scene}}
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Result<SubmittedSettings> SubmittedSettings::FromJson(const std::string& text) {
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
  if (json.is_discarded() || !json.is_object()) return Error{"job settings are not JSON"};
  SubmittedSettings s;
  try {
    s.tolerance = json.at("tolerance").get<double>();
    s.max_rays = json.at("max_rays").get<uint64_t>();
    s.max_seconds = json.at("max_seconds").get<double>();
    s.sampler = json.at("sampler").get<std::string>();
    s.patches = json.at("patches").get<uint64_t>();
    s.scene = json.at("scene").get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    return Error{std::string("job settings: ") + e.what()};
  }
  return s;
}

Result<JobSummary> ReadJobSummary(store::JobStore& store, const store::JobRecord& record) {
  JobSummary summary;
  summary.record = record;
  Result<SubmittedSettings> settings = SubmittedSettings::FromJson(record.spec.settings);
  if (!settings) return Error{"job " + std::to_string(record.id) + ": " + settings.error()};
  summary.settings = *settings;
  Result<std::vector<store::RoundRecord>> rounds = store.ListRounds(record.id);
  RADFARM_RETURN_IF_ERROR(rounds);
  for (const store::RoundRecord& r : *rounds) {
    summary.rays += r.rays;
    summary.seconds += r.duration_seconds;
  }
  summary.rounds = static_cast<uint32_t>(rounds->size());
  if (!rounds->empty()) summary.unshot_fraction = rounds->back().unshot_fraction;
  if (record.state == store::JobState::kDone) {
    Result<std::optional<std::string>> reason = store.LoadLatestStopReason(record.id);
    RADFARM_RETURN_IF_ERROR(reason);
    summary.stop_reason = *reason;
  }
  return summary;
}

std::string StopReasonOf(const JobSummary& s) {
  if (s.stop_reason) return *s.stop_reason;
  if (s.unshot_fraction <= s.settings.tolerance) return kStopConverged;
  if (s.settings.max_rays > 0 && s.rays >= s.settings.max_rays) return kStopRayBudget;
  return kStopTimeBudget;
}

}  // namespace radfarm::daemon
