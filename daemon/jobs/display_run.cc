#include "daemon/jobs/display_run.h"

#include <algorithm>
#include <string>

namespace radfarm::daemon {

std::optional<double> DisplaySecondsLeft(const DisplayRun& run, uint64_t now_ms) {
  if (run.rays_done == 0 || run.rays_done >= run.forecast_rays || now_ms <= run.started_ms) {
    return std::nullopt;
  }
  const double seconds = double(now_ms - run.started_ms) / 1000;
  return seconds * double(run.forecast_rays - run.rays_done) / double(run.rays_done);
}

size_t PiecePoints(size_t points, size_t agents) {
  const size_t share =
      (points + 4 * std::max<size_t>(1, agents) - 1) / (4 * std::max<size_t>(1, agents));
  return std::clamp(share, kMinLeasePoints, protocol::kMaxLeasePoints);
}

protocol::PointLeaseMsg MakePointLease(store::JobId job, const PieceLease& lease,
                                       const PointWork& work, const protocol::SceneHash& context,
                                       uint32_t lease_ms) {
  protocol::PointLeaseMsg m;
  m.lease = {static_cast<uint64_t>(job), lease.piece_id, lease.attempt};
  m.context_hash = context;
  m.seed = work.seed;
  m.near_radius = work.near_radius;
  m.direct = work.direct;
  m.first_index = work.first_index + lease.begin;
  m.lease_ms = std::max<uint32_t>(1, lease_ms);
  if (work.start()) {
    m.start_sections = work.start_sections;
    m.start_patches = static_cast<uint32_t>(lease.end - lease.begin);
    return m;
  }
  if (work.scores()) {
    m.score_elements = static_cast<uint32_t>(lease.end - lease.begin);
    return m;
  }
  m.points.reserve(lease.end - lease.begin);
  for (size_t i = lease.begin; i < lease.end; ++i) {
    m.points.push_back({work.points[i].position, work.points[i].normal});
  }
  if (!work.gather.empty()) {
    m.gather_rays = work.gather_rays;
    m.gather.assign(work.gather.begin() + lease.begin, work.gather.begin() + lease.end);
  }
  m.lease_ms = std::max<uint32_t>(1, lease_ms);
  return m;
}

namespace {

Status CheckCount(const char* list, size_t values, bool asked, size_t points) {
  const size_t due = asked ? points : 0;
  if (values == due) return Ok{};
  return Error{"PointResult: " + std::to_string(values) + " " + list + " values where " +
               std::to_string(due) + " are due"};
}

}  // namespace

Result<PointValues> ValuesOfResult(const protocol::PointResultMsg& result, const PointWork& work,
                                   size_t begin, size_t end) {
  const size_t points = end - begin;
  RADFARM_RETURN_IF_ERROR(CheckCount("near", result.near.size(), work.near_radius > 0, points));
  RADFARM_RETURN_IF_ERROR(CheckCount("direct", result.direct.size(), work.direct, points));
  RADFARM_RETURN_IF_ERROR(
      CheckCount("gathered", result.gathered.size(), !work.gather.empty(), points));
  RADFARM_RETURN_IF_ERROR(
      CheckCount("punctual", result.punctual.size(), work.start() && work.start_punctual, points));
  RADFARM_RETURN_IF_ERROR(CheckCount("scores", result.scores.size(), work.scores(), points));
  PointValues values;
  values.near.assign(result.near.begin(), result.near.end());
  values.direct = result.direct;
  values.gathered = result.gathered;
  values.punctual = result.punctual;
  values.scores = result.scores;
  values.rays = result.rays;
  return values;
}

}  // namespace radfarm::daemon
