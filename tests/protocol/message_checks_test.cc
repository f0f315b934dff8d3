// Every value rule of CheckMessage, seen from the receiving end: a frame carrying a bad value is
// rejected by the decoder with a reason that names the message and the field.
#include "protocol/message_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "protocol/frame_codec.h"
#include "tests/protocol/sample_messages.h"

namespace radfarm::protocol {
namespace {

using testing::SampleMessages;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

template <typename T>
T Sample() {
  for (const Message& m : SampleMessages()) {
    if (const T* t = std::get_if<T>(&m)) return *t;
  }
  return T{};
}

// The message, written in `version`, is rejected on decode, with `text` in the reason.
void ExpectRejected(const Message& message, const std::string& text,
                    uint16_t version = kProtocolVersion) {
  EXPECT_FALSE(CheckMessage(message)) << text;
  Result<DecodedFrame> r = DecodeFrame(EncodeFrame(message, version));
  ASSERT_FALSE(r) << "accepted: " << text;
  EXPECT_NE(r.error().find(text), std::string::npos) << r.error();
}

TEST(ProtocolCheckTest, Hello) {
  HelloMsg m = Sample<HelloMsg>();
  m.min_version = 0;
  ExpectRejected(m, "Hello: bad version range");
  m = Sample<HelloMsg>();
  m.min_version = 3;
  m.max_version = 2;
  ExpectRejected(m, "Hello: bad version range");
  for (std::string name : {std::string(), std::string(65, 'a'), std::string("bad name"),
                           std::string("evil\nlog"), std::string("nul\0x", 5)}) {
    m = Sample<HelloMsg>();
    m.agent_name = name;
    ExpectRejected(m, "Hello: agent name");
  }
  m = Sample<HelloMsg>();
  m.threads = 0;
  ExpectRejected(m, "Hello: threads");
  m.threads = kMaxAgentThreads + 1;
  ExpectRejected(m, "Hello: threads");
  EXPECT_TRUE(IsValidAgentName(std::string(kMaxAgentNameBytes, 'z')));
}

TEST(ProtocolCheckTest, ChallengeAndWelcome) {
  ChallengeMsg c = Sample<ChallengeMsg>();
  c.version = 0;
  ExpectRejected(c, "Challenge: version 0");
  WelcomeMsg w = Sample<WelcomeMsg>();
  w.heartbeat_interval_ms = 0;
  ExpectRejected(w, "Welcome: heartbeat");
  w = Sample<WelcomeMsg>();
  w.max_frame_bytes = kMinPeerFrameBytes - 1;
  ExpectRejected(w, "Welcome: max frame bytes");
}

TEST(ProtocolCheckTest, HeartbeatNumbersMustBeFiniteAndNonNegative) {
  for (double bad : {kNaN, kInf, -kInf, -1.0}) {
    HeartbeatMsg m = Sample<HeartbeatMsg>();
    m.load = bad;
    ExpectRejected(m, "Heartbeat: load");
    m = Sample<HeartbeatMsg>();
    m.rays_per_second = bad;
    ExpectRejected(m, "Heartbeat: rays_per_second");
  }
}

TEST(ProtocolCheckTest, LeaseAssignment) {
  LeaseAssignmentMsg m = Sample<LeaseAssignmentMsg>();
  m.patch_count = 0;
  ExpectRejected(m, "LeaseAssignment: patch_count 0");
  m = Sample<LeaseAssignmentMsg>();
  m.batches[0].shooter = m.patch_count;
  ExpectRejected(m, "LeaseAssignment batch 0: shooter 5000 >= patch_count 5000");
  m = Sample<LeaseAssignmentMsg>();
  m.batches[1].ray_count = 0;
  ExpectRejected(m, "LeaseAssignment batch 1: ray_count 0");
  m = Sample<LeaseAssignmentMsg>();
  m.batches[0].first_ray = UINT64_MAX - 10;
  ExpectRejected(m, "overflows");
  m = Sample<LeaseAssignmentMsg>();
  m.sampler = static_cast<SamplerKind>(9);
  ExpectRejected(m, "unknown sampler 9");
  for (double bad : {kNaN, kInf, 0.0, -1.0, 90.5}) {
    m = Sample<LeaseAssignmentMsg>();
    m.grid_step_degrees = bad;
    ExpectRejected(m, "grid_step_degrees");
  }
  m = Sample<LeaseAssignmentMsg>();
  m.sampler = SamplerKind::kSobol;
  m.grid_step_degrees = 0;  // unused by sobol: any finite value is fine
  EXPECT_TRUE(CheckMessage(m));
  m.grid_step_degrees = kNaN;  // but never a non-finite one
  ExpectRejected(m, "grid_step_degrees not finite");
  m = Sample<LeaseAssignmentMsg>();
  m.lease_ms = 0;
  ExpectRejected(m, "lease_ms 0");
  m = Sample<LeaseAssignmentMsg>();
  m.batches.clear();
  ExpectRejected(m, "LeaseAssignment: 0 batches");
  m = Sample<LeaseAssignmentMsg>();
  m.batches[2].batch_id = m.batches[0].batch_id;
  ExpectRejected(m, "appears twice");
}

TEST(ProtocolCheckTest, LeaseResult) {
  // Hits as structs (version 4): packed hits (version 5) out of order or weightless do not even
  // unpack (ProtocolMalformedTest.ALeaseResultsHitsMustBeInItsVersionsForm).
  const uint16_t structs = kMinProtocolVersion;
  LeaseResultMsg m = Sample<LeaseResultMsg>();
  m.results[0].hits[1].weight = 0;
  ExpectRejected(m, "LeaseResult result 0: hit 1 (patch 17) has weight 0", structs);
  m = Sample<LeaseResultMsg>();
  m.results[0].hits[2].patch = m.results[0].hits[1].patch;
  ExpectRejected(m, "LeaseResult result 0: hit 2 patch 17 not above", structs);
  m = Sample<LeaseResultMsg>();
  std::swap(m.results[0].hits[0], m.results[0].hits[1]);
  ExpectRejected(m, "not above", structs);
  for (double bad : {kNaN, kInf, -0.5}) {
    m = Sample<LeaseResultMsg>();
    m.results[2].compute_seconds = bad;
    ExpectRejected(m, "LeaseResult result 2: compute_seconds");
  }
  m = Sample<LeaseResultMsg>();
  m.results.clear();
  ExpectRejected(m, "LeaseResult: 0 results");
}

TEST(ProtocolCheckTest, PointLease) {
  PointLeaseMsg m = Sample<PointLeaseMsg>();
  m.points.clear();
  ExpectRejected(m, "PointLease: 0 points");
  m = Sample<PointLeaseMsg>();
  m.points.resize(kMaxLeasePoints + 1, m.points[0]);
  m.gather.clear();
  ExpectRejected(m, "PointLease: 16385 points");
  m = Sample<PointLeaseMsg>();
  m.first_index = UINT64_MAX - 1;
  ExpectRejected(m, "PointLease: first_index overflows");
  for (double bad : {kNaN, kInf}) {
    m = Sample<PointLeaseMsg>();
    m.points[1].position.y = bad;
    ExpectRejected(m, "PointLease: point 1 is not finite");
  }
  m = Sample<PointLeaseMsg>();
  m.points[0].normal = {0, 2, 0};
  ExpectRejected(m, "PointLease: point 0 is not finite with a unit normal");
  for (double bad : {kNaN, kInf, -0.5}) {
    m = Sample<PointLeaseMsg>();
    m.near_radius = bad;
    ExpectRejected(m, "PointLease: near_radius");
  }
  m = Sample<PointLeaseMsg>();
  m.gather.push_back(1);
  ExpectRejected(m, "PointLease: 3 gather flags for 2 points");
  m = Sample<PointLeaseMsg>();
  m.gather[1] = 2;
  ExpectRejected(m, "PointLease: a gather flag other than 0 or 1");
  for (uint32_t bad : {0u, kMaxPointGatherRays + 1}) {
    m = Sample<PointLeaseMsg>();
    m.gather_rays = bad;
    ExpectRejected(m, "PointLease: gather_rays");
  }
  // No point of the piece gathers: no ray asked for, and the lease stands.
  m = Sample<PointLeaseMsg>();
  m.gather = {0, 0};
  m.gather_rays = 0;
  EXPECT_TRUE(CheckMessage(m));
  m = Sample<PointLeaseMsg>();
  m.near_radius = 0;
  m.direct = false;
  m.gather.clear();
  ExpectRejected(m, "PointLease: asks for nothing");
  m = Sample<PointLeaseMsg>();
  m.lease_ms = 0;
  ExpectRejected(m, "PointLease: lease_ms 0");
}

TEST(ProtocolCheckTest, PointResult) {
  PointResultMsg m = Sample<PointResultMsg>();
  m.near.clear();
  m.direct.clear();
  m.gathered.clear();
  ExpectRejected(m, "PointResult: 0 values");
  m = Sample<PointResultMsg>();
  m.direct.resize(kMaxLeasePoints + 1);
  ExpectRejected(m, "PointResult: 16385 values");
  m = Sample<PointResultMsg>();
  m.near[0] = 7;
  ExpectRejected(m, "PointResult: a near flag other than 0 or 1");
  m = Sample<PointResultMsg>();
  m.direct[1].g = kNaN;
  ExpectRejected(m, "PointResult: direct value 1 not finite");
  m = Sample<PointResultMsg>();
  m.gathered[0].b = -kInf;
  ExpectRejected(m, "PointResult: gathered value 0 not finite");
  for (double bad : {kNaN, kInf, -0.5}) {
    m = Sample<PointResultMsg>();
    m.compute_seconds = bad;
    ExpectRejected(m, "PointResult: compute_seconds");
  }
}

TEST(ProtocolCheckTest, LeaseReturn) {
  LeaseReturnMsg m = Sample<LeaseReturnMsg>();
  m.leases.clear();
  ExpectRejected(m, "LeaseReturn: 0 leases");
  m = Sample<LeaseReturnMsg>();
  m.leases.resize(kMaxLeaseReturnEntries + 1);
  ExpectRejected(m, "LeaseReturn: 65537 leases");
  m = Sample<LeaseReturnMsg>();
  m.reason = static_cast<LeaseReturnReason>(4);
  ExpectRejected(m, "LeaseReturn: unknown reason 4");
}

TEST(ProtocolCheckTest, SceneMessages) {
  SceneRequestMsg r = Sample<SceneRequestMsg>();
  r.max_length = 0;
  ExpectRejected(r, "SceneRequest: max_length 0");
  r.max_length = kMaxSceneChunkBytes + 1;
  ExpectRejected(r, "SceneRequest: max_length");
  SceneChunkMsg c = Sample<SceneChunkMsg>();
  c.data.clear();
  ExpectRejected(c, "SceneChunk: 0 data bytes");
  c = Sample<SceneChunkMsg>();
  c.data.resize(kMaxSceneChunkBytes + 1);
  c.total_size = uint64_t{1} << 40;
  ExpectRejected(c, "SceneChunk: 1048577 data bytes");
  c = Sample<SceneChunkMsg>();
  c.offset = c.total_size - 10;
  ExpectRejected(c, "beyond total_size");
  c = Sample<SceneChunkMsg>();
  c.offset = UINT64_MAX;
  ExpectRejected(c, "beyond total_size");
}

TEST(ProtocolCheckTest, DrainAndClose) {
  DrainMsg d = Sample<DrainMsg>();
  d.mode = static_cast<DrainMode>(2);
  ExpectRejected(d, "Drain: unknown mode 2");
  CloseMsg c = Sample<CloseMsg>();
  c.code = CloseCode::kBlocklisted;  // the last code (version 4)
  EXPECT_TRUE(CheckMessage(c));
  c.code = static_cast<CloseCode>(7);
  ExpectRejected(c, "Close: unknown code 7");
  c = Sample<CloseMsg>();
  c.detail = std::string(kMaxCloseDetailBytes + 1, 'x');
  ExpectRejected(c, "Close: detail");
  c.detail = "line\nbreak";
  ExpectRejected(c, "Close: detail");
}

}  // namespace
}  // namespace radfarm::protocol
