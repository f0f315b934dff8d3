// The farm's wire messages as plain C++ values. The daemon and the agent work with these; only
// protocol/*.cc sees the FlatBuffers schema (schema/*.fbs), whose tables these mirror field for
// field. docs/PROTOCOL.md describes every field, who sends what, and when.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/batch.h"
#include "core/rgb.h"
#include "core/solver_settings.h"
#include "core/vec3.h"
#include "protocol/limits.h"

namespace radfarm::protocol {

using Bytes32 = std::array<uint8_t, 32>;
using Nonce = Bytes32;
using Tag = Bytes32;        // HMAC-SHA-256
using SceneHash = Bytes32;  // SHA-256 of a scene blob

// Wire values are fixed (schema/common.fbs); append, never renumber.
enum class DrainMode : uint8_t { kFinishLeases = 0, kReturnLeases = 1 };
enum class LeaseReturnReason : uint8_t {
  kDraining = 0,
  kSceneUnavailable = 1,
  kOverloaded = 2,
  kFailed = 3
};
enum class CloseCode : uint8_t {
  kNormal = 0,
  kShutdown = 1,
  kProtocolError = 2,
  kAuthFailed = 3,
  kVersionMismatch = 4,
  kInternalError = 5,
  kBlocklisted = 6  // version 4
};

// One attempt at one batch of one job: the master's unit of bookkeeping.
struct LeaseRef {
  uint64_t job_id = 0;
  uint64_t batch_id = 0;
  uint32_t attempt_id = 0;
  bool operator==(const LeaseRef&) const = default;
};

// --- Handshake (agent opens) ---

struct HelloMsg {  // agent -> master
  uint16_t min_version = kMinProtocolVersion;
  uint16_t max_version = kProtocolVersion;
  std::string agent_name;  // 1..kMaxAgentNameBytes of [A-Za-z0-9._:@-]
  uint32_t threads = 0;    // 1..kMaxAgentThreads
  Nonce nonce{};
  bool operator==(const HelloMsg&) const = default;
};

struct ChallengeMsg {    // master -> agent
  uint16_t version = 0;  // chosen version, used by every later frame
  Nonce nonce{};
  bool operator==(const ChallengeMsg&) const = default;
};

struct ProofMsg {  // agent -> master
  Tag tag{};
  bool operator==(const ProofMsg&) const = default;
};

struct WelcomeMsg {  // master -> agent
  Tag tag{};
  uint64_t agent_id = 0;
  uint32_t heartbeat_interval_ms = 0;  // >= 1
  uint32_t max_frame_bytes = 0;        // >= kMinPeerFrameBytes
  bool operator==(const WelcomeMsg&) const = default;
};

// --- Steady state ---

struct HeartbeatMsg {          // both ways
  double load = 0;             // finite, >= 0
  double rays_per_second = 0;  // finite, >= 0
  uint32_t leases_held = 0;
  bool operator==(const HeartbeatMsg&) const = default;
};

// The agent's record of one batch it leased: a LeaseBatch with its lease's job fields
// (protocol/batch_convert.h, BatchOf). Not a message: no frame carries one alone.
struct AssignedBatch {
  LeaseRef lease;
  uint32_t round = 0;
  uint32_t shooter = 0;  // < patch_count
  uint64_t first_ray = 0;
  uint32_t ray_count = 0;  // >= 1; first_ray + ray_count does not overflow
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::kSobol;
  double grid_step_degrees = 1;  // finite; in (0, 90] for the grid sampler
  SceneHash scene_hash{};
  uint32_t patch_count = 0;  // >= 1
  uint32_t lease_ms = 0;     // >= 1
  bool operator==(const AssignedBatch&) const = default;
};

// What became of one leased batch: its result and the lease it answers. Not a message: each entry
// of a LeaseResultMsg is one.
struct BatchOutcome {
  LeaseRef lease;
  std::vector<PatchHits> hits;  // strictly increasing patch id, no zero weights
  uint64_t escaped_weight = 0;
  uint64_t escaped_rays = 0;
  uint64_t back_weight = 0;
  uint64_t back_rays = 0;
  double compute_seconds = 0;  // finite, >= 0
  bool operator==(const BatchOutcome&) const = default;
};

// One batch of a lease: rays [first_ray, first_ray + ray_count) of `shooter`, attempt `attempt_id`.
struct LeaseBatch {
  uint64_t batch_id = 0;
  uint32_t attempt_id = 0;
  uint32_t shooter = 0;  // < patch_count
  uint64_t first_ray = 0;
  uint32_t ray_count = 0;  // >= 1; first_ray + ray_count does not overflow
  bool operator==(const LeaseBatch&) const = default;
};

// Version 2: many batches of one job and round in one frame.
struct LeaseAssignmentMsg {  // master -> agent
  uint64_t job_id = 0;
  uint32_t round = 0;
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::kSobol;
  double grid_step_degrees = 1;
  SceneHash scene_hash{};
  uint32_t patch_count = 0;         // >= 1
  uint32_t lease_ms = 0;            // >= 1
  std::vector<LeaseBatch> batches;  // 1..kMaxLeaseBatches, distinct batch ids
  bool operator==(const LeaseAssignmentMsg&) const = default;
};

// Version 2: results of batches of one or more leases, in one frame.
struct LeaseResultMsg {               // agent -> master
  std::vector<BatchOutcome> results;  // 1..kMaxLeaseBatches, each as BatchOutcome's rules
  bool operator==(const LeaseResultMsg&) const = default;
};

// Version 2: batches the master took over; the agent drops those it has not started.
struct LeaseRevokeMsg {          // master -> agent
  std::vector<LeaseRef> leases;  // 1..kMaxLeaseBatches
  bool operator==(const LeaseRevokeMsg&) const = default;
};

struct LeaseReturnMsg {          // agent -> master
  std::vector<LeaseRef> leases;  // 1..kMaxLeaseReturnEntries
  LeaseReturnReason reason = LeaseReturnReason::kDraining;
  bool operator==(const LeaseReturnMsg&) const = default;
};

struct CancelMsg {  // master -> agent
  uint64_t job_id = 0;
  bool operator==(const CancelMsg&) const = default;
};

// --- The display's points (version 6) ---

// A point the display needs the light at: on a surface, facing along its unit normal.
struct LeasedPoint {
  Vec3 position;  // finite
  Vec3 normal;    // finite, unit
  bool operator==(const LeasedPoint&) const = default;
};

// Points [first_index, first_index + points.size()) of one step of a job's display (a piece of a
// display/point_work.h PointWork), traced against the point context the hash names (fetched as a
// scene is: codec/point_context_blob.h). `lease.batch_id` names the piece. From version 7, a
// piece of a direct-light start instead (start_sections > 0, core/direct_start.h): patches
// [first_index, first_index + start_patches) of the context's scene, no points, `direct` set. From
// version 8, a piece of a refinement step's light scores (score_elements > 0,
// mesh/light_scores.h): elements [first_index, first_index + score_elements) of the context's
// score work, no points, nothing else asked.
struct PointLeaseMsg {  // master -> agent
  LeaseRef lease;
  SceneHash context_hash{};
  uint64_t seed = 0;
  double near_radius = 0;           // finite, >= 0; 0: not asked
  bool direct = false;              // the direct light at every point
  uint32_t gather_rays = 0;         // <= kMaxPointGatherRays; >= 1 where a gather flag is 1
  uint64_t first_index = 0;         // first_index + points.size() does not overflow
  std::vector<LeasedPoint> points;  // 1..kMaxLeasePoints
  std::vector<uint8_t> gather;      // empty, or 0 or 1 per point: the points that gather
  uint32_t lease_ms = 0;            // >= 1
  uint32_t start_sections = 0;      // <= kMaxStartSections; 0: point work
  uint32_t start_patches = 0;       // 1..kMaxLeasePoints with start_sections, else 0
  uint32_t score_elements = 0;      // 1..kMaxLeasePoints for score work, else 0
  bool operator==(const PointLeaseMsg&) const = default;
};

// The values of a PointLease's points, in order (display/point_work.h PointValues): each list
// empty where the lease did not ask for it, else one value per point.
struct PointResultMsg {  // agent -> master
  LeaseRef lease;
  std::vector<uint8_t> near;   // 0 or 1 per point
  std::vector<Rgb> direct;     // finite
  std::vector<Rgb> gathered;   // finite
  uint64_t rays = 0;           // shadow and gathering rays cast
  double compute_seconds = 0;  // finite, >= 0
  std::vector<Rgb> punctual;   // finite; a start's punctual lights' share per patch (version 7)
  std::vector<double> scores;  // finite, >= 0; score work's per element (version 8)
  bool operator==(const PointResultMsg&) const = default;
};

// --- Scene distribution ---

struct SceneRequestMsg {  // agent -> master
  SceneHash scene_hash{};
  uint64_t offset = 0;
  uint32_t max_length = kMaxSceneChunkBytes;  // 1..kMaxSceneChunkBytes
  bool operator==(const SceneRequestMsg&) const = default;
};

struct SceneChunkMsg {  // master -> agent
  SceneHash scene_hash{};
  uint64_t total_size = 0;    // of the compressed scene (scene_packing.h), >= 1
  uint64_t offset = 0;        // offset + data.size() <= total_size
  std::vector<uint8_t> data;  // 1..kMaxSceneChunkBytes of the compressed scene
  uint64_t scene_size = 0;    // of the uncompressed blob the hash names, >= 1
  bool operator==(const SceneChunkMsg&) const = default;
};

struct SceneUnavailableMsg {  // master -> agent
  SceneHash scene_hash{};
  bool operator==(const SceneUnavailableMsg&) const = default;
};

// --- Control ---

struct DrainMsg {  // master -> agent
  DrainMode mode = DrainMode::kFinishLeases;
  bool exit_after = false;
  bool operator==(const DrainMsg&) const = default;
};

struct CloseMsg {  // both ways, any state; the sender closes the connection after it
  CloseCode code = CloseCode::kNormal;
  std::string detail;  // 0..kMaxCloseDetailBytes of printable ASCII
  bool operator==(const CloseMsg&) const = default;
};

// In the order of the schema's Payload union, less its retired slots (the codec takes each
// message's wire type from its table, wire_encode.cc).
using Message =
    std::variant<HelloMsg, ChallengeMsg, ProofMsg, WelcomeMsg, HeartbeatMsg, LeaseReturnMsg,
                 CancelMsg, SceneRequestMsg, SceneChunkMsg, SceneUnavailableMsg, DrainMsg, CloseMsg,
                 LeaseAssignmentMsg, LeaseResultMsg, LeaseRevokeMsg, PointLeaseMsg, PointResultMsg>;

// A verified incoming frame.
struct DecodedFrame {
  uint16_t version = 0;  // the protocol version the sender wrote it in
  Message message;
};

std::string_view MessageName(const Message& message);
// Whether `message` exists in protocol `version` (the Lease messages from 2 on).
bool InVersion(const Message& message, uint16_t version);
std::string_view CloseCodeName(CloseCode code);

}  // namespace radfarm::protocol
