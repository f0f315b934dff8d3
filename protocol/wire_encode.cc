// C++ messages -> FlatBuffers tables. Enum values are mapped one by one rather than cast, so the
// wire values stay fixed whatever happens to core's enums.
#include <type_traits>
#include <vector>

#include "core/packed_hits.h"
#include "protocol/limits.h"
#include "protocol/wire_convert.h"

namespace radfarm::protocol {
namespace {

using flatbuffers::FlatBufferBuilder;
using flatbuffers::Offset;

wire::Bytes32 ToWire(const Bytes32& b) {
  return wire::Bytes32(flatbuffers::span<const uint8_t, 32>(b));
}

wire::LeaseRef ToWire(const LeaseRef& l) { return {l.job_id, l.batch_id, l.attempt_id}; }

wire::SamplerKind ToWire(SamplerKind k) {
  switch (k) {
    case SamplerKind::kGrid:
      return wire::SamplerKind::Grid;
    case SamplerKind::kRandom:
      return wire::SamplerKind::Random;
    case SamplerKind::kSobol:
      return wire::SamplerKind::Sobol;
  }
  // Out-of-range values pass through so tests can send them; the receiver rejects them.
  return static_cast<wire::SamplerKind>(k);
}

Offset<wire::Hello> Build(FlatBufferBuilder& fbb, const HelloMsg& m) {
  const wire::Bytes32 nonce = ToWire(m.nonce);
  return wire::CreateHello(fbb, m.min_version, m.max_version, fbb.CreateString(m.agent_name),
                           m.threads, &nonce);
}

Offset<wire::Challenge> Build(FlatBufferBuilder& fbb, const ChallengeMsg& m) {
  const wire::Bytes32 nonce = ToWire(m.nonce);
  return wire::CreateChallenge(fbb, m.version, &nonce);
}

Offset<wire::Proof> Build(FlatBufferBuilder& fbb, const ProofMsg& m) {
  const wire::Bytes32 tag = ToWire(m.tag);
  return wire::CreateProof(fbb, &tag);
}

Offset<wire::Welcome> Build(FlatBufferBuilder& fbb, const WelcomeMsg& m) {
  const wire::Bytes32 tag = ToWire(m.tag);
  return wire::CreateWelcome(fbb, &tag, m.agent_id, m.heartbeat_interval_ms, m.max_frame_bytes);
}

Offset<wire::Heartbeat> Build(FlatBufferBuilder& fbb, const HeartbeatMsg& m) {
  return wire::CreateHeartbeat(fbb, m.load, m.rays_per_second, m.leases_held);
}

Offset<wire::LeaseReturn> Build(FlatBufferBuilder& fbb, const LeaseReturnMsg& m) {
  std::vector<wire::LeaseRef> wire_leases;
  wire_leases.reserve(m.leases.size());
  for (const LeaseRef& l : m.leases) wire_leases.push_back(ToWire(l));
  const auto leases = fbb.CreateVectorOfStructs(wire_leases.data(), wire_leases.size());
  return wire::CreateLeaseReturn(fbb, leases, static_cast<wire::LeaseReturnReason>(m.reason));
}

Offset<wire::Cancel> Build(FlatBufferBuilder& fbb, const CancelMsg& m) {
  return wire::CreateCancel(fbb, m.job_id);
}

Offset<wire::SceneRequest> Build(FlatBufferBuilder& fbb, const SceneRequestMsg& m) {
  const wire::Bytes32 hash = ToWire(m.scene_hash);
  return wire::CreateSceneRequest(fbb, &hash, m.offset, m.max_length);
}

Offset<wire::SceneChunk> Build(FlatBufferBuilder& fbb, const SceneChunkMsg& m) {
  const auto data = fbb.CreateVector(m.data);
  const wire::Bytes32 hash = ToWire(m.scene_hash);
  return wire::CreateSceneChunk(fbb, &hash, m.total_size, m.offset, data, m.scene_size);
}

Offset<wire::SceneUnavailable> Build(FlatBufferBuilder& fbb, const SceneUnavailableMsg& m) {
  const wire::Bytes32 hash = ToWire(m.scene_hash);
  return wire::CreateSceneUnavailable(fbb, &hash);
}

Offset<wire::Drain> Build(FlatBufferBuilder& fbb, const DrainMsg& m) {
  return wire::CreateDrain(fbb, static_cast<wire::DrainMode>(m.mode), m.exit_after);
}

Offset<wire::Close> Build(FlatBufferBuilder& fbb, const CloseMsg& m) {
  const auto detail = fbb.CreateString(m.detail);
  return wire::CreateClose(fbb, static_cast<wire::CloseCode>(m.code), detail);
}

Offset<wire::LeaseAssignment> Build(FlatBufferBuilder& fbb, const LeaseAssignmentMsg& m) {
  std::vector<wire::LeaseBatch> wire_batches;
  wire_batches.reserve(m.batches.size());
  for (const LeaseBatch& b : m.batches) {
    wire_batches.emplace_back(b.batch_id, b.first_ray, b.shooter, b.ray_count, b.attempt_id);
  }
  const auto batches = fbb.CreateVectorOfStructs(wire_batches.data(), wire_batches.size());
  const wire::Bytes32 hash = ToWire(m.scene_hash);
  return wire::CreateLeaseAssignment(fbb, m.job_id, m.round, m.seed, ToWire(m.sampler),
                                     m.grid_step_degrees, &hash, m.patch_count, m.lease_ms,
                                     batches);
}

Offset<wire::LeaseResult> Build(FlatBufferBuilder& fbb, const LeaseResultMsg& m, uint16_t version) {
  std::vector<wire::BatchTally> tallies;
  tallies.reserve(m.results.size());
  for (const BatchOutcome& r : m.results) {
    tallies.emplace_back(ToWire(r.lease), r.escaped_weight, r.escaped_rays, r.back_weight,
                         r.back_rays, r.compute_seconds, static_cast<uint32_t>(r.hits.size()));
  }
  const auto batches = fbb.CreateVectorOfStructs(tallies.data(), tallies.size());
  std::vector<wire::PatchHit> wire_hits;
  if (version >= kPackedHitsVersion) {
    std::vector<uint8_t> packed;
    for (const BatchOutcome& r : m.results) AppendPackedHits(r.hits, &packed);
    const auto packed_hits = fbb.CreateVector(packed);
    const auto hits = fbb.CreateVectorOfStructs(wire_hits.data(), 0);
    return wire::CreateLeaseResult(fbb, batches, hits, packed_hits);
  }
  for (const BatchOutcome& r : m.results) {
    for (const PatchHits& h : r.hits) wire_hits.emplace_back(h.patch, h.weight);
  }
  const auto hits = fbb.CreateVectorOfStructs(wire_hits.data(), wire_hits.size());
  return wire::CreateLeaseResult(fbb, batches, hits);
}

Offset<wire::LeaseRevoke> Build(FlatBufferBuilder& fbb, const LeaseRevokeMsg& m) {
  std::vector<wire::LeaseRef> wire_leases;
  wire_leases.reserve(m.leases.size());
  for (const LeaseRef& l : m.leases) wire_leases.push_back(ToWire(l));
  const auto leases = fbb.CreateVectorOfStructs(wire_leases.data(), wire_leases.size());
  return wire::CreateLeaseRevoke(fbb, leases);
}

Offset<flatbuffers::Vector<const wire::PointValue*>> PointValues(FlatBufferBuilder& fbb,
                                                                 const std::vector<Rgb>& values) {
  std::vector<wire::PointValue> out;
  out.reserve(values.size());
  for (const Rgb& c : values) out.emplace_back(c.r, c.g, c.b);
  return fbb.CreateVectorOfStructs(out.data(), out.size());
}

Offset<wire::PointLease> Build(FlatBufferBuilder& fbb, const PointLeaseMsg& m) {
  std::vector<wire::LeasedPoint> wire_points;
  wire_points.reserve(m.points.size());
  for (const LeasedPoint& p : m.points) {
    wire_points.emplace_back(p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y,
                             p.normal.z);
  }
  const auto points = fbb.CreateVectorOfStructs(wire_points.data(), wire_points.size());
  const auto gather = m.gather.empty() ? 0 : fbb.CreateVector(m.gather);
  const wire::LeaseRef lease = ToWire(m.lease);
  const wire::Bytes32 hash = ToWire(m.context_hash);
  return wire::CreatePointLease(fbb, &lease, &hash, m.seed, m.near_radius, m.direct, m.gather_rays,
                                m.first_index, points, gather, m.lease_ms, m.start_sections,
                                m.start_patches, m.score_elements);
}

Offset<wire::PointResult> Build(FlatBufferBuilder& fbb, const PointResultMsg& m) {
  const auto near = m.near.empty() ? 0 : fbb.CreateVector(m.near);
  const auto direct = m.direct.empty() ? 0 : PointValues(fbb, m.direct);
  const auto gathered = m.gathered.empty() ? 0 : PointValues(fbb, m.gathered);
  const auto punctual = m.punctual.empty() ? 0 : PointValues(fbb, m.punctual);
  const auto scores = m.scores.empty() ? 0 : fbb.CreateVector(m.scores);
  const wire::LeaseRef lease = ToWire(m.lease);
  return wire::CreatePointResult(fbb, &lease, near, direct, gathered, m.rays, m.compute_seconds,
                                 punctual, scores);
}

// A table as the frame's payload; its union tag comes from the table's type, so the C++ messages
// need not follow the union's order (retired slots have no message).
template <typename Table>
Offset<void> AsPayload(Offset<Table> table, wire::Payload* type) {
  *type = wire::PayloadTraits<Table>::enum_value;
  return table.Union();
}

}  // namespace

Offset<void> BuildPayload(FlatBufferBuilder& fbb, const Message& message, uint16_t version,
                          wire::Payload* type) {
  return std::visit(
      [&fbb, version, type](const auto& m) {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, LeaseResultMsg>) {
          return AsPayload(Build(fbb, m, version), type);
        } else {
          return AsPayload(Build(fbb, m), type);
        }
      },
      message);
}

}  // namespace radfarm::protocol
