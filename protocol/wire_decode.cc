// FlatBuffers tables -> C++ messages, for frames that already passed the verifier. The verifier
// guarantees every offset and length is inside the buffer; this adds what it does not check.
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "core/packed_hits.h"
#include "protocol/limits.h"
#include "protocol/wire_convert.h"

namespace radfarm::protocol {
namespace {

Error Missing(const char* message, const char* field) {
  return Error{std::string(message) + ": missing " + field};
}

Bytes32 FromWire(const wire::Bytes32& b) {
  Bytes32 out;
  std::memcpy(out.data(), b.bytes()->Data(), out.size());
  return out;
}

LeaseRef FromWire(const wire::LeaseRef& l) { return {l.job_id(), l.batch_id(), l.attempt_id()}; }

// The verifier checks a struct vector's length word, not its elements' alignment; a hand-made
// frame could place 8-byte fields off alignment, and reading them would be undefined.
template <typename T>
bool IsAligned(const flatbuffers::Vector<const T*>& v) {
  // An empty vector reads nothing; FlatBuffers aligns it only to 4 bytes (PreAlign skips a zero
  // length), so a LeaseResult whose batches hit no patch would otherwise be refused.
  return v.size() == 0 || reinterpret_cast<uintptr_t>(v.Data()) % alignof(T) == 0;
}

Result<Message> Read(const wire::Hello& t) {
  if (!t.agent_name()) return Missing("Hello", "agent_name");
  if (!t.nonce()) return Missing("Hello", "nonce");
  return Message{HelloMsg{t.min_version(), t.max_version(), t.agent_name()->str(), t.threads(),
                          FromWire(*t.nonce())}};
}

Result<Message> Read(const wire::Challenge& t) {
  if (!t.nonce()) return Missing("Challenge", "nonce");
  return Message{ChallengeMsg{t.version(), FromWire(*t.nonce())}};
}

Result<Message> Read(const wire::Proof& t) {
  if (!t.tag()) return Missing("Proof", "tag");
  return Message{ProofMsg{FromWire(*t.tag())}};
}

Result<Message> Read(const wire::Welcome& t) {
  if (!t.tag()) return Missing("Welcome", "tag");
  return Message{
      WelcomeMsg{FromWire(*t.tag()), t.agent_id(), t.heartbeat_interval_ms(), t.max_frame_bytes()}};
}

Result<Message> Read(const wire::Heartbeat& t) {
  return Message{HeartbeatMsg{t.load(), t.rays_per_second(), t.leases_held()}};
}

Result<SamplerKind> ReadSampler(wire::SamplerKind kind, const char* message) {
  switch (kind) {
    case wire::SamplerKind::Grid:
      return SamplerKind::kGrid;
    case wire::SamplerKind::Random:
      return SamplerKind::kRandom;
    case wire::SamplerKind::Sobol:
      return SamplerKind::kSobol;
    default:
      break;
  }
  return Error{std::string(message) + ": unknown sampler " +
               std::to_string(static_cast<unsigned>(kind))};
}

Result<Message> Read(const wire::LeaseReturn& t) {
  if (!t.leases()) return Missing("LeaseReturn", "leases");
  if (!IsAligned(*t.leases())) return Error{"LeaseReturn: misaligned leases"};
  LeaseReturnMsg m;
  m.leases.reserve(t.leases()->size());
  for (const wire::LeaseRef* l : *t.leases()) m.leases.push_back(FromWire(*l));
  // Same numbering as the schema; CheckMessage rejects values past the last one.
  m.reason = static_cast<LeaseReturnReason>(t.reason());
  return Message{std::move(m)};
}

Result<Message> Read(const wire::LeaseAssignment& t) {
  if (!t.scene_hash()) return Missing("LeaseAssignment", "scene_hash");
  if (!t.batches()) return Missing("LeaseAssignment", "batches");
  if (!IsAligned(*t.batches())) return Error{"LeaseAssignment: misaligned batches"};
  LeaseAssignmentMsg m;
  Result<SamplerKind> sampler = ReadSampler(t.sampler(), "LeaseAssignment");
  RADFARM_RETURN_IF_ERROR(sampler);
  m.sampler = *sampler;
  m.job_id = t.job_id();
  m.round = t.round();
  m.seed = t.seed();
  m.grid_step_degrees = t.grid_step_degrees();
  m.scene_hash = FromWire(*t.scene_hash());
  m.patch_count = t.patch_count();
  m.lease_ms = t.lease_ms();
  m.batches.reserve(t.batches()->size());
  for (const wire::LeaseBatch* b : *t.batches()) {
    m.batches.push_back(
        {b->batch_id(), b->attempt_id(), b->shooter(), b->first_ray(), b->ray_count()});
  }
  return Message{std::move(m)};
}

// The batches' counts, with their hits read from `hits` (versions 2-4) or `packed_hits` (5 on).
Result<Message> ReadLeaseResult(const wire::LeaseResult& t, uint16_t version) {
  if (!t.batches()) return Missing("LeaseResult", "batches");
  if (!t.hits()) return Missing("LeaseResult", "hits");
  if (!IsAligned(*t.batches())) return Error{"LeaseResult: misaligned batches"};
  if (!IsAligned(*t.hits())) return Error{"LeaseResult: misaligned hits"};
  const bool packed = version >= kPackedHitsVersion;
  if (packed && !t.packed_hits()) return Missing("LeaseResult", "packed_hits (version 5 on)");
  if (packed && t.hits()->size() != 0) {
    return Error{"LeaseResult: hits in version-4 form in a version-" + std::to_string(version) +
                 " frame (version 5 on packs them in packed_hits)"};
  }
  if (!packed && t.packed_hits()) {
    return Error{"LeaseResult: packed_hits in a version-" + std::to_string(version) +
                 " frame (they exist from version 5)"};
  }
  // The hit counts must slice the hits exactly: check the sum before reading any slice.
  uint64_t total = 0;
  for (const wire::BatchTally* b : *t.batches()) total += b->hit_count();
  if (!packed && total != t.hits()->size()) {
    return Error{"LeaseResult: hit counts add up to " + std::to_string(total) + ", not the " +
                 std::to_string(t.hits()->size()) + " hits sent"};
  }
  const std::span<const uint8_t> bytes =
      packed ? std::span<const uint8_t>(t.packed_hits()->data(), t.packed_hits()->size())
             : std::span<const uint8_t>();
  size_t at = 0;
  LeaseResultMsg m;
  m.results.reserve(t.batches()->size());
  uint32_t next = 0;
  for (const wire::BatchTally* b : *t.batches()) {
    BatchOutcome r;
    r.lease = FromWire(b->lease());
    if (packed) {
      const std::string wrong = ReadPackedHits(bytes, &at, b->hit_count(), &r.hits);
      if (!wrong.empty()) {
        return Error{"LeaseResult: batch " + std::to_string(m.results.size()) +
                     "'s packed hits: " + wrong};
      }
    } else {
      r.hits.reserve(b->hit_count());
      for (uint32_t k = 0; k < b->hit_count(); ++k, ++next) {
        const wire::PatchHit* h = t.hits()->Get(next);
        r.hits.push_back({h->patch(), h->weight()});
      }
    }
    r.escaped_weight = b->escaped_weight();
    r.escaped_rays = b->escaped_rays();
    r.back_weight = b->back_weight();
    r.back_rays = b->back_rays();
    r.compute_seconds = b->compute_seconds();
    m.results.push_back(std::move(r));
  }
  if (at != bytes.size()) {
    return Error{"LeaseResult: " + std::to_string(bytes.size() - at) +
                 " bytes of packed hits after the last batch's"};
  }
  return Message{std::move(m)};
}

Result<Message> Read(const wire::LeaseRevoke& t) {
  if (!t.leases()) return Missing("LeaseRevoke", "leases");
  if (!IsAligned(*t.leases())) return Error{"LeaseRevoke: misaligned leases"};
  LeaseRevokeMsg m;
  m.leases.reserve(t.leases()->size());
  for (const wire::LeaseRef* l : *t.leases()) m.leases.push_back(FromWire(*l));
  return Message{std::move(m)};
}

Result<Message> Read(const wire::PointLease& t) {
  if (!t.lease()) return Missing("PointLease", "lease");
  if (!t.context_hash()) return Missing("PointLease", "context_hash");
  if (!t.points()) return Missing("PointLease", "points");
  if (!IsAligned(*t.points())) return Error{"PointLease: misaligned points"};
  PointLeaseMsg m;
  m.lease = FromWire(*t.lease());
  m.context_hash = FromWire(*t.context_hash());
  m.seed = t.seed();
  m.near_radius = t.near_radius();
  m.direct = t.direct();
  m.gather_rays = t.gather_rays();
  m.first_index = t.first_index();
  m.points.reserve(t.points()->size());
  for (const wire::LeasedPoint* p : *t.points()) {
    m.points.push_back({{p->px(), p->py(), p->pz()}, {p->nx(), p->ny(), p->nz()}});
  }
  if (t.gather()) m.gather.assign(t.gather()->begin(), t.gather()->end());
  m.lease_ms = t.lease_ms();
  m.start_sections = t.start_sections();
  m.start_patches = t.start_patches();
  m.score_elements = t.score_elements();
  return Message{std::move(m)};
}

// A list of point values, or an error naming it.
Status ReadPointValues(const flatbuffers::Vector<const wire::PointValue*>* in, const char* field,
                       std::vector<Rgb>* out) {
  if (!in) return Ok{};
  if (!IsAligned(*in)) return Error{std::string("PointResult: misaligned ") + field};
  out->reserve(in->size());
  for (const wire::PointValue* v : *in) out->push_back({v->r(), v->g(), v->b()});
  return Ok{};
}

Result<Message> Read(const wire::PointResult& t) {
  if (!t.lease()) return Missing("PointResult", "lease");
  PointResultMsg m;
  m.lease = FromWire(*t.lease());
  if (t.near()) m.near.assign(t.near()->begin(), t.near()->end());
  RADFARM_RETURN_IF_ERROR(ReadPointValues(t.direct(), "direct", &m.direct));
  RADFARM_RETURN_IF_ERROR(ReadPointValues(t.gathered(), "gathered", &m.gathered));
  RADFARM_RETURN_IF_ERROR(ReadPointValues(t.punctual(), "punctual", &m.punctual));
  if (t.scores()) m.scores.assign(t.scores()->begin(), t.scores()->end());
  m.rays = t.rays();
  m.compute_seconds = t.compute_seconds();
  return Message{std::move(m)};
}

Result<Message> Read(const wire::Cancel& t) { return Message{CancelMsg{t.job_id()}}; }

Result<Message> Read(const wire::SceneRequest& t) {
  if (!t.scene_hash()) return Missing("SceneRequest", "scene_hash");
  return Message{SceneRequestMsg{FromWire(*t.scene_hash()), t.offset(), t.max_length()}};
}

Result<Message> Read(const wire::SceneChunk& t) {
  if (!t.scene_hash()) return Missing("SceneChunk", "scene_hash");
  if (!t.data()) return Missing("SceneChunk", "data");
  return Message{SceneChunkMsg{FromWire(*t.scene_hash()), t.total_size(), t.offset(),
                               std::vector<uint8_t>(t.data()->begin(), t.data()->end()),
                               t.scene_size()}};
}

Result<Message> Read(const wire::SceneUnavailable& t) {
  if (!t.scene_hash()) return Missing("SceneUnavailable", "scene_hash");
  return Message{SceneUnavailableMsg{FromWire(*t.scene_hash())}};
}

Result<Message> Read(const wire::Drain& t) {
  return Message{DrainMsg{static_cast<DrainMode>(t.mode()), t.exit_after()}};
}

Result<Message> Read(const wire::Close& t) {
  return Message{CloseMsg{static_cast<CloseCode>(t.code()), t.detail() ? t.detail()->str() : ""}};
}

// Reads the table of union type T, or reports it missing.
template <typename T>
Result<Message> ReadAs(const wire::Frame& frame) {
  const T* table = frame.payload_as<T>();
  if (!table) return Error{"frame: missing payload"};
  return Read(*table);
}

// A slot kept in the union only so later members keep their numbers (schema/frame.fbs).
Error Retired(const wire::Frame& frame, const char* message) {
  return Error{"frame: message type " +
               std::to_string(static_cast<unsigned>(frame.payload_type())) + " (" + message +
               ", protocol version 1) is retired"};
}

}  // namespace

Result<Message> ReadPayload(const wire::Frame& frame) {
  using P = wire::Payload;
  switch (frame.payload_type()) {
    case P::Hello:
      return ReadAs<wire::Hello>(frame);
    case P::Challenge:
      return ReadAs<wire::Challenge>(frame);
    case P::Proof:
      return ReadAs<wire::Proof>(frame);
    case P::Welcome:
      return ReadAs<wire::Welcome>(frame);
    case P::Heartbeat:
      return ReadAs<wire::Heartbeat>(frame);
    case P::RetiredBatchAssignment:
      return Retired(frame, "BatchAssignment");
    case P::RetiredBatchResult:
      return Retired(frame, "BatchResult");
    case P::LeaseReturn:
      return ReadAs<wire::LeaseReturn>(frame);
    case P::Cancel:
      return ReadAs<wire::Cancel>(frame);
    case P::SceneRequest:
      return ReadAs<wire::SceneRequest>(frame);
    case P::SceneChunk:
      return ReadAs<wire::SceneChunk>(frame);
    case P::SceneUnavailable:
      return ReadAs<wire::SceneUnavailable>(frame);
    case P::Drain:
      return ReadAs<wire::Drain>(frame);
    case P::Close:
      return ReadAs<wire::Close>(frame);
    case P::LeaseAssignment:
      return ReadAs<wire::LeaseAssignment>(frame);
    case P::LeaseResult: {
      const wire::LeaseResult* table = frame.payload_as<wire::LeaseResult>();
      if (!table) return Error{"frame: missing payload"};
      return ReadLeaseResult(*table, frame.version());
    }
    case P::LeaseRevoke:
      return ReadAs<wire::LeaseRevoke>(frame);
    case P::PointLease:
      return ReadAs<wire::PointLease>(frame);
    case P::PointResult:
      return ReadAs<wire::PointResult>(frame);
    default:
      break;
  }
  return Error{"frame: unknown message type " +
               std::to_string(static_cast<unsigned>(frame.payload_type()))};
}

}  // namespace radfarm::protocol
