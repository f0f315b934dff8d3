#include "tests/protocol/sample_messages.h"

namespace radfarm::protocol::testing {

Bytes32 Pattern(uint8_t seed) {
  Bytes32 b;
  for (size_t i = 0; i < b.size(); ++i) b[i] = static_cast<uint8_t>(seed + 37 * i);
  return b;
}

std::vector<Message> SampleMessages() {
  const LeaseRef lease{0x0102030405060708ull, 0x1112131415161718ull, 3};
  std::vector<uint8_t> scene_bytes(300);
  for (size_t i = 0; i < scene_bytes.size(); ++i) scene_bytes[i] = static_cast<uint8_t>(i * 7);
  return {
      HelloMsg{1, 1, "render-node-07.example:4", 48, Pattern(1)},
      ChallengeMsg{1, Pattern(2)},
      ProofMsg{Pattern(3)},
      WelcomeMsg{Pattern(4), 77, 2500, kDefaultMaxFrameBytes},
      HeartbeatMsg{3.25, 1.5e8, 12},
      LeaseReturnMsg{{lease, {2, 3, 4}}, LeaseReturnReason::kSceneUnavailable},
      CancelMsg{42},
      SceneRequestMsg{Pattern(6), 1 << 20, 4096},
      SceneChunkMsg{Pattern(7), 1 << 21, 1 << 20, scene_bytes, 5 << 21},
      SceneUnavailableMsg{Pattern(8)},
      DrainMsg{DrainMode::kReturnLeases, true},
      CloseMsg{CloseCode::kShutdown, "master shutting down: maintenance"},
      LeaseAssignmentMsg{lease.job_id,
                         9,
                         0xdeadbeefcafef00dull,
                         SamplerKind::kGrid,
                         2.5,
                         Pattern(9),
                         5000,
                         30000,
                         {{lease.batch_id, 3, 1234, uint64_t{1} << 40, 65536},
                          {lease.batch_id + 1, 4, 4999, 0, 1},
                          {lease.batch_id + 7, 3, 0, 12, 300}}},
      LeaseResultMsg{{
          BatchOutcome{lease,
                       {{0, 5}, {17, 1}, {4999, uint64_t{1} << 50}},
                       11,
                       11,
                       uint64_t{1} << 33,
                       2,
                       0.125},
          BatchOutcome{{lease.job_id, lease.batch_id + 1, 4}, {}, 1, 1, 0, 0, 0},
          BatchOutcome{{lease.job_id, lease.batch_id + 7, 3}, {{3, 300}}, 0, 0, 0, 0, 1e-3},
      }},
      LeaseRevokeMsg{{lease, {lease.job_id, lease.batch_id + 7, 3}}},
      PointLeaseMsg{lease,
                    Pattern(10),
                    0x0badc0ffee0ddf00ull,
                    0.375,
                    true,
                    128,
                    uint64_t{1} << 35,
                    {{{1.5, -2.25, 1e-300}, {0, 1, 0}}, {{0, 0, 548.75}, {0.6, 0, -0.8}}},
                    {1, 0},
                    45000,
                    0,
                    0,
                    0},
      PointResultMsg{lease,
                     {0, 1},
                     {{0.5, 0.25, 1e-9}, {12, 0, 3}},
                     {{0.1, -1e-17, 0.3}, {0, 0, 0}},
                     uint64_t{1} << 40,
                     0.0625,
                     {},
                     {}},
  };
}

std::vector<Message> StartSamples() {
  const LeaseRef lease{0x0102030405060708ull, 0x1111222233334444ull, 3};
  return {
      PointLeaseMsg{lease, Pattern(11), 77, 0, true, 0, 4096, {}, {}, 60000, 8, 1024, 0},
      PointResultMsg{lease, {}, {{0.5, 0.25, 1e-9}}, {}, 320, 0.5, {{0.25, 0, 1e-3}}, {}},
  };
}

std::vector<Message> ScoreSamples() {
  const LeaseRef lease{0x0102030405060708ull, 0x1111222233334444ull, 4};
  const PointLeaseMsg scores{lease, Pattern(12), 0, 0, false, 0, 2048, {}, {}, 60000, 0, 0, 3};
  const PointResultMsg result{lease, {}, {}, {}, 0, 0.25, {}, {0, 1.5, 1e-300}};
  return {scores, result};
}

}  // namespace radfarm::protocol::testing
