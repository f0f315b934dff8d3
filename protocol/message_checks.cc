#include "protocol/message_checks.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace radfarm::protocol {
namespace {

std::string Str(uint64_t v) { return std::to_string(v); }

Status Fail(std::string_view message, const std::string& why) {
  return Error{std::string(message) + ": " + why};
}

bool IsNonNegativeFinite(double v) { return std::isfinite(v) && v >= 0; }

bool IsPrintableAscii(std::string_view s) {
  for (char c : s) {
    if (c < 0x20 || c > 0x7e) return false;
  }
  return true;
}

Status Check(const HelloMsg& m) {
  if (m.min_version < 1 || m.min_version > m.max_version) {
    return Fail("Hello", "bad version range " + Str(m.min_version) + ".." + Str(m.max_version));
  }
  if (!IsValidAgentName(m.agent_name)) {
    return Fail("Hello", "agent name must be 1.." + Str(kMaxAgentNameBytes) +
                             " characters of [A-Za-z0-9._:@-]");
  }
  if (m.threads < 1 || m.threads > kMaxAgentThreads) {
    return Fail("Hello", "threads " + Str(m.threads) + " not in 1.." + Str(kMaxAgentThreads));
  }
  return Ok{};
}

Status Check(const ChallengeMsg& m) {
  if (m.version < 1) return Fail("Challenge", "version 0");
  return Ok{};
}

Status Check(const ProofMsg&) { return Ok{}; }

Status Check(const WelcomeMsg& m) {
  if (m.heartbeat_interval_ms < 1) return Fail("Welcome", "heartbeat interval 0");
  if (m.max_frame_bytes < kMinPeerFrameBytes) {
    return Fail("Welcome",
                "max frame bytes " + Str(m.max_frame_bytes) + " < " + Str(kMinPeerFrameBytes));
  }
  return Ok{};
}

Status Check(const HeartbeatMsg& m) {
  if (!IsNonNegativeFinite(m.load)) return Fail("Heartbeat", "load not finite and >= 0");
  if (!IsNonNegativeFinite(m.rays_per_second)) {
    return Fail("Heartbeat", "rays_per_second not finite and >= 0");
  }
  return Ok{};
}

bool IsKnown(SamplerKind k) {
  return k == SamplerKind::kGrid || k == SamplerKind::kRandom || k == SamplerKind::kSobol;
}

// The rules of one batch of a LeaseAssignment.
Status CheckBatchRange(std::string_view message, uint32_t shooter, uint64_t first_ray,
                       uint32_t ray_count, uint32_t patch_count) {
  if (shooter >= patch_count) {
    return Fail(message, "shooter " + Str(shooter) + " >= patch_count " + Str(patch_count));
  }
  if (ray_count < 1) return Fail(message, "ray_count 0");
  if (first_ray > UINT64_MAX - ray_count) return Fail(message, "first_ray + ray_count overflows");
  return Ok{};
}

// The rules of a LeaseAssignment's job fields.
Status CheckJobFields(std::string_view message, SamplerKind sampler, double grid_step_degrees,
                      uint32_t patch_count, uint32_t lease_ms) {
  if (patch_count < 1) return Fail(message, "patch_count 0");
  if (!IsKnown(sampler)) {
    return Fail(message, "unknown sampler " + Str(static_cast<uint8_t>(sampler)));
  }
  if (!std::isfinite(grid_step_degrees)) return Fail(message, "grid_step_degrees not finite");
  if (sampler == SamplerKind::kGrid &&
      !(grid_step_degrees > 0 && grid_step_degrees <= kMaxGridStepDegrees)) {
    return Fail(message, "grid_step_degrees not in (0, 90]");
  }
  if (lease_ms < 1) return Fail(message, "lease_ms 0");
  return Ok{};
}

Status Check(const LeaseAssignmentMsg& m) {
  if (m.batches.empty() || m.batches.size() > kMaxLeaseBatches) {
    return Fail("LeaseAssignment",
                Str(m.batches.size()) + " batches, not 1.." + Str(kMaxLeaseBatches));
  }
  RADFARM_RETURN_IF_ERROR(
      CheckJobFields("LeaseAssignment", m.sampler, m.grid_step_degrees, m.patch_count, m.lease_ms));
  for (size_t k = 0; k < m.batches.size(); ++k) {
    const LeaseBatch& b = m.batches[k];
    RADFARM_RETURN_IF_ERROR(CheckBatchRange("LeaseAssignment batch " + Str(k), b.shooter,
                                            b.first_ray, b.ray_count, m.patch_count));
  }
  std::vector<uint64_t> ids;
  ids.reserve(m.batches.size());
  for (const LeaseBatch& b : m.batches) ids.push_back(b.batch_id);
  std::sort(ids.begin(), ids.end());
  if (const auto repeat = std::adjacent_find(ids.begin(), ids.end()); repeat != ids.end()) {
    return Fail("LeaseAssignment", "batch " + Str(*repeat) + " appears twice");
  }
  return Ok{};
}

Status CheckResult(std::string_view name, const BatchOutcome& m) {
  for (size_t i = 0; i < m.hits.size(); ++i) {
    if (m.hits[i].weight == 0) {
      return Fail(name, "hit " + Str(i) + " (patch " + Str(m.hits[i].patch) + ") has weight 0");
    }
    if (i > 0 && m.hits[i].patch <= m.hits[i - 1].patch) {
      return Fail(name, "hit " + Str(i) + " patch " + Str(m.hits[i].patch) +
                            " not above the previous patch " + Str(m.hits[i - 1].patch));
    }
  }
  if (!IsNonNegativeFinite(m.compute_seconds)) {
    return Fail(name, "compute_seconds not finite and >= 0");
  }
  return Ok{};
}

Status Check(const LeaseResultMsg& m) {
  if (m.results.empty() || m.results.size() > kMaxLeaseBatches) {
    return Fail("LeaseResult", Str(m.results.size()) + " results, not 1.." + Str(kMaxLeaseBatches));
  }
  for (size_t k = 0; k < m.results.size(); ++k) {
    RADFARM_RETURN_IF_ERROR(CheckResult("LeaseResult result " + Str(k), m.results[k]));
  }
  return Ok{};
}

Status Check(const LeaseRevokeMsg& m) {
  if (m.leases.empty() || m.leases.size() > kMaxLeaseBatches) {
    return Fail("LeaseRevoke", Str(m.leases.size()) + " leases, not 1.." + Str(kMaxLeaseBatches));
  }
  return Ok{};
}

Status Check(const LeaseReturnMsg& m) {
  if (m.leases.empty() || m.leases.size() > kMaxLeaseReturnEntries) {
    return Fail("LeaseReturn",
                Str(m.leases.size()) + " leases, not 1.." + Str(kMaxLeaseReturnEntries));
  }
  if (static_cast<uint8_t>(m.reason) > static_cast<uint8_t>(LeaseReturnReason::kFailed)) {
    return Fail("LeaseReturn", "unknown reason " + Str(static_cast<uint8_t>(m.reason)));
  }
  return Ok{};
}

// Flags of one byte each: 0 or 1 (they become std::vector<bool>).
bool AreFlags(const std::vector<uint8_t>& flags) {
  return std::all_of(flags.begin(), flags.end(), [](uint8_t f) { return f <= 1; });
}

Status CheckStartLease(const PointLeaseMsg& m) {
  const size_t n = m.start_patches;
  if (n == 0 || n > kMaxLeasePoints) {
    return Fail("PointLease", Str(n) + " start patches, not 1.." + Str(kMaxLeasePoints));
  }
  if (m.start_sections > kMaxStartSections) {
    return Fail("PointLease",
                "start_sections " + Str(m.start_sections) + " not in 1.." + Str(kMaxStartSections));
  }
  if (!m.points.empty() || !m.gather.empty() || m.near_radius != 0 || !m.direct) {
    return Fail("PointLease", "a start lease with points, gathering or near flags");
  }
  if (m.first_index > UINT64_MAX - n) return Fail("PointLease", "first_index overflows");
  if (m.lease_ms < 1) return Fail("PointLease", "lease_ms 0");
  return Ok{};
}

Status CheckScoreLease(const PointLeaseMsg& m) {
  const size_t n = m.score_elements;
  if (n > kMaxLeasePoints) {
    return Fail("PointLease", Str(n) + " score elements, not 1.." + Str(kMaxLeasePoints));
  }
  if (!m.points.empty() || !m.gather.empty() || m.near_radius != 0 || m.direct ||
      m.start_sections != 0 || m.start_patches != 0) {
    return Fail("PointLease", "a score lease with points, lights, gathering or start patches");
  }
  if (m.first_index > UINT64_MAX - n) return Fail("PointLease", "first_index overflows");
  if (m.lease_ms < 1) return Fail("PointLease", "lease_ms 0");
  return Ok{};
}

Status Check(const PointLeaseMsg& m) {
  if (m.score_elements > 0) return CheckScoreLease(m);
  if (m.start_sections > 0) return CheckStartLease(m);
  if (m.start_patches != 0) return Fail("PointLease", "start_patches without start_sections");
  const size_t n = m.points.size();
  if (n == 0 || n > kMaxLeasePoints) {
    return Fail("PointLease", Str(n) + " points, not 1.." + Str(kMaxLeasePoints));
  }
  if (m.first_index > UINT64_MAX - n) return Fail("PointLease", "first_index overflows");
  for (size_t i = 0; i < n; ++i) {
    const LeasedPoint& p = m.points[i];
    const double length = Length(p.normal);
    if (!IsFinite(p.position) || !IsFinite(p.normal) || std::abs(length - 1) > 1e-6) {
      return Fail("PointLease", "point " + Str(i) + " is not finite with a unit normal");
    }
  }
  if (!IsNonNegativeFinite(m.near_radius)) {
    return Fail("PointLease", "near_radius not finite and >= 0");
  }
  if (!m.gather.empty()) {
    if (m.gather.size() != n) {
      return Fail("PointLease", Str(m.gather.size()) + " gather flags for " + Str(n) + " points");
    }
    if (!AreFlags(m.gather)) return Fail("PointLease", "a gather flag other than 0 or 1");
    // A step may gather at no point of a piece (or anywhere, its rays fitted to nothing): its
    // gathered values are then zeros, and no ray is asked for.
    const bool any = std::find(m.gather.begin(), m.gather.end(), 1) != m.gather.end();
    if ((any && m.gather_rays < 1) || m.gather_rays > kMaxPointGatherRays) {
      return Fail("PointLease", "gather_rays " + Str(m.gather_rays) + " not in " +
                                    (any ? "1" : "0") + ".." + Str(kMaxPointGatherRays));
    }
  }
  if (m.near_radius == 0 && !m.direct && m.gather.empty()) {
    return Fail("PointLease", "asks for nothing");
  }
  if (m.lease_ms < 1) return Fail("PointLease", "lease_ms 0");
  return Ok{};
}

Status Check(const PointResultMsg& m) {
  const size_t most = std::max(
      {m.near.size(), m.direct.size(), m.gathered.size(), m.punctual.size(), m.scores.size()});
  if (most == 0 || most > kMaxLeasePoints) {
    return Fail("PointResult", Str(most) + " values, not 1.." + Str(kMaxLeasePoints));
  }
  if (!AreFlags(m.near)) return Fail("PointResult", "a near flag other than 0 or 1");
  for (const auto& [values, name] :
       {std::pair{&m.direct, "direct"}, std::pair{&m.gathered, "gathered"},
        std::pair{&m.punctual, "punctual"}}) {
    for (size_t i = 0; i < values->size(); ++i) {
      if (!(*values)[i].IsFinite()) {
        return Fail("PointResult", std::string(name) + " value " + Str(i) + " not finite");
      }
    }
  }
  for (size_t i = 0; i < m.scores.size(); ++i) {
    if (!IsNonNegativeFinite(m.scores[i])) {
      return Fail("PointResult", "score " + Str(i) + " not finite and >= 0");
    }
  }
  if (!IsNonNegativeFinite(m.compute_seconds)) {
    return Fail("PointResult", "compute_seconds not finite and >= 0");
  }
  return Ok{};
}

Status Check(const CancelMsg&) { return Ok{}; }

Status Check(const SceneRequestMsg& m) {
  if (m.max_length < 1 || m.max_length > kMaxSceneChunkBytes) {
    return Fail("SceneRequest",
                "max_length " + Str(m.max_length) + " not in 1.." + Str(kMaxSceneChunkBytes));
  }
  return Ok{};
}

Status Check(const SceneChunkMsg& m) {
  if (m.data.empty() || m.data.size() > kMaxSceneChunkBytes) {
    return Fail("SceneChunk",
                Str(m.data.size()) + " data bytes, not 1.." + Str(kMaxSceneChunkBytes));
  }
  if (m.offset > m.total_size || m.data.size() > m.total_size - m.offset) {
    return Fail("SceneChunk", "bytes " + Str(m.offset) + "+" + Str(m.data.size()) +
                                  " beyond total_size " + Str(m.total_size));
  }
  if (m.scene_size == 0) return Fail("SceneChunk", "scene_size 0");
  return Ok{};
}

Status Check(const SceneUnavailableMsg&) { return Ok{}; }

Status Check(const DrainMsg& m) {
  if (static_cast<uint8_t>(m.mode) > static_cast<uint8_t>(DrainMode::kReturnLeases)) {
    return Fail("Drain", "unknown mode " + Str(static_cast<uint8_t>(m.mode)));
  }
  return Ok{};
}

Status Check(const CloseMsg& m) {
  if (static_cast<uint8_t>(m.code) > static_cast<uint8_t>(CloseCode::kBlocklisted)) {
    return Fail("Close", "unknown code " + Str(static_cast<uint8_t>(m.code)));
  }
  if (m.detail.size() > kMaxCloseDetailBytes || !IsPrintableAscii(m.detail)) {
    return Fail("Close", "detail must be at most " + Str(kMaxCloseDetailBytes) +
                             " bytes of printable ASCII");
  }
  return Ok{};
}

}  // namespace

bool IsValidAgentName(std::string_view name) {
  if (name.empty() || name.size() > kMaxAgentNameBytes) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == ':' || c == '@' || c == '-';
    if (!ok) return false;
  }
  return true;
}

Status CheckOutcomeValues(const BatchOutcome& result) { return CheckResult("result", result); }

Status CheckMessage(const Message& message) {
  return std::visit([](const auto& m) { return Check(m); }, message);
}

}  // namespace radfarm::protocol
