// The real radfarm-agent against the fake master: point leases (protocol version 6), pieces of a
// real display's work, answered with exactly the values a PointTracer gives them here, and
// dropped by a Cancel.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <optional>

#include "codec/patch_scene_codec.h"
#include "codec/point_context_blob.h"
#include "core/direct_light.h"
#include "display/display_plan.h"
#include "display/point_context.h"
#include "mesh/patch_mesh.h"
#include "protocol/limits.h"
#include "protocol/scene_transfer.h"
#include "solve/local_solve.h"
#include "tests/agent/agent_process.h"
#include "tests/agent/fake_master.h"
#include "tests/agent/test_farm.h"
#include "tests/mesh/test_scenes.h"

namespace radfarm::agent::testing {
namespace {

// One step of a display: its work and the context it is traced against, as the master has them.
struct DisplayStep {
  PointWork work;
  PointContext context;
  std::vector<uint8_t> blob;  // EncodePointContext
  protocol::SceneHash hash{};
};

// The lease of points [begin, end) of `step`'s work, as the master cuts it (PieceOf).
protocol::PointLeaseMsg PointLeaseOf(const protocol::LeaseRef& ref, const DisplayStep& step,
                                     size_t begin, size_t end) {
  const PointWork piece = PieceOf(step.work, begin, end);
  protocol::PointLeaseMsg lease;
  lease.lease = ref;
  lease.context_hash = step.hash;
  lease.seed = piece.seed;
  lease.near_radius = piece.near_radius;
  lease.direct = piece.direct;
  lease.gather_rays = piece.gather.empty() ? 0 : piece.gather_rays;
  lease.first_index = piece.first_index;
  for (const ReceiverPoint& point : piece.points) {
    lease.points.push_back({point.position, point.normal});
  }
  lease.gather.assign(piece.gather.begin(), piece.gather.end());
  lease.lease_ms = 60000;
  return lease;
}

// The Cornell box meshed coarsely and solved, and its display's first two steps: the direct
// light's (a context that does not gather) and the next (one that does).
class AgentPointsTest : public ::testing::Test {
 protected:
  AgentPointsTest() : secret_(TestSecret(0x6b)), master_(secret_, Heartbeats(250, true)) {
    WriteSecretFile(dir_.File("key"), secret_);
  }

  void SetUp() override {
    Result<PatchMesh> built = PatchMesh::Build(::radfarm::testing::CornellBox(), {90}, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    mesh_.emplace(std::move(*built));
    SolverSettings solver;
    solver.gather_rays = 256;
    solver.threads = 2;
    const SolveResult solution = Solve(mesh_->patch_scene(), solver);
    const DisplayTopology topology = mesh_->display_topology();
    DisplaySettings settings;
    settings.seed = 7;
    settings.threads = 2;
    settings.emitters = EmittersInDirectStart(mesh_->patch_scene(), solver);
    settings.rays_per_light = DirectLightRaysPerLight(mesh_->patch_scene(), solver);
    DisplayPlan plan({topology, mesh_->patch_scene(), mesh_->patch_size(), solution.radiosity,
                      solution.direct_light},
                     settings);
    const std::vector<uint8_t> scene = codec::EncodePatchScene(mesh_->patch_scene());
    for (int k = 0; k < 2; ++k) {
      ASSERT_NE(plan.work(), nullptr) << "step " << k;
      DisplayStep step{*plan.work(), plan.context(), {}, {}};
      step.blob = codec::EncodePointContext(scene, step.context);
      step.hash = protocol::HashScene(step.blob);
      master_.AddScene(step.blob);
      const PointTracer tracer(mesh_->patch_scene(), step.context);
      plan.Apply(tracer.Trace(step.work, 0, step.work.points.size(), 2));
      steps_.push_back(std::move(step));
    }
    ASSERT_FALSE(steps_[0].context.gathers());
    ASSERT_TRUE(steps_[1].context.gathers());
  }

  std::unique_ptr<AgentProcess> StartAgent(unsigned threads) {
    auto agent =
        std::make_unique<AgentProcess>(AgentArgs(master_.address(), dir_.File("key"), threads));
    EXPECT_TRUE(master_.WaitFor([](const Record& r) { return r.open == 1; })) << agent->Log();
    EXPECT_TRUE(agent->WaitForLog("connected to " + master_.address())) << agent->Log();
    return agent;
  }

  // What a PointTracer of this process gives points [begin, end) of `step`, on one thread.
  PointValues TraceHere(const DisplayStep& step, size_t begin, size_t end) const {
    const PointTracer tracer(mesh_->patch_scene(), step.context);
    const PointWork piece = PieceOf(step.work, begin, end);
    return tracer.Trace(piece, 0, piece.points.size(), 1);
  }

  std::optional<protocol::PointResultMsg> WaitResult(const protocol::LeaseRef& lease,
                                                     const AgentProcess& agent) {
    std::optional<protocol::PointResultMsg> found;
    const bool got = master_.WaitFor([&](const Record& r) {
      for (const auto& result : r.All<protocol::PointResultMsg>()) {
        if (result.lease == lease) found = result;
      }
      return found.has_value();
    });
    EXPECT_TRUE(got) << "no result for job " << lease.job_id << " piece " << lease.batch_id << "\n"
                     << agent.Log();
    return found;
  }

  ScratchDir dir_;
  protocol::FarmSecret secret_;
  FakeMaster master_;
  std::optional<PatchMesh> mesh_;
  std::vector<DisplayStep> steps_;
};

void ExpectSameValues(const protocol::PointResultMsg& got, const PointValues& want) {
  ASSERT_EQ(got.near.size(), want.near.size());
  for (size_t i = 0; i < want.near.size(); ++i) {
    EXPECT_EQ(got.near[i], want.near[i] ? 1 : 0) << "point " << i;
  }
  ASSERT_EQ(got.direct.size(), want.direct.size());
  for (size_t i = 0; i < want.direct.size(); ++i) {
    ASSERT_EQ(got.direct[i], want.direct[i]) << "point " << i;
  }
  ASSERT_EQ(got.gathered.size(), want.gathered.size());
  for (size_t i = 0; i < want.gathered.size(); ++i) {
    ASSERT_EQ(got.gathered[i], want.gathered[i]) << "point " << i;
  }
  EXPECT_EQ(got.rays, want.rays);
  EXPECT_GE(got.compute_seconds, 0);
}

TEST_F(AgentPointsTest, APointLeaseIsAnsweredWithTheValuesAPointTracerGivesHere) {
  std::unique_ptr<AgentProcess> agent = StartAgent(2);
  // A piece of each step from the middle of its list: its points keyed as in the whole.
  const DisplayStep& direct = steps_[0];
  const DisplayStep& gathering = steps_[1];
  const size_t d0 = direct.work.points.size() / 3,
               d1 = std::min(direct.work.points.size(), d0 + 300);
  const size_t g0 = gathering.work.points.size() / 4;
  const size_t g1 = std::min(gathering.work.points.size(), g0 + 300);
  const PointValues direct_here = TraceHere(direct, d0, d1);
  const PointValues gathered_here = TraceHere(gathering, g0, g1);
  ASSERT_FALSE(direct_here.direct.empty());
  ASSERT_FALSE(gathered_here.gathered.empty()) << "the piece should gather";

  const protocol::LeaseRef first{3, 1, 0};
  const protocol::LeaseRef second{3, 2, 0};
  master_.Send({protocol::Message(PointLeaseOf(first, direct, d0, d1)),
                protocol::Message(PointLeaseOf(second, gathering, g0, g1))});
  const std::optional<protocol::PointResultMsg> got_direct = WaitResult(first, *agent);
  const std::optional<protocol::PointResultMsg> got_gathered = WaitResult(second, *agent);
  ASSERT_TRUE(got_direct && got_gathered);
  ExpectSameValues(*got_direct, direct_here);
  ExpectSameValues(*got_gathered, gathered_here);

  // Both contexts stay in memory: another piece of the first is traced without a fetch.
  const protocol::LeaseRef third{3, 3, 0};
  master_.Send(protocol::Message(PointLeaseOf(third, direct, 0, d0)));
  const std::optional<protocol::PointResultMsg> got_third = WaitResult(third, *agent);
  ASSERT_TRUE(got_third);
  ExpectSameValues(*got_third, TraceHere(direct, 0, d0));
  const Record record = master_.Snapshot();
  EXPECT_EQ(record.fetches.at(direct.hash), 1);
  EXPECT_EQ(record.fetches.at(gathering.hash), 1);
  EXPECT_TRUE(record.All<protocol::LeaseReturnMsg>().empty()) << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentPointsTest, CancelDropsTheJobsQueuedAndRunningPointLeases) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  const DisplayStep& gathering = steps_[1];
  // Warm the context first, so job 1's leases are queued behind a busy worker, not waiting for it.
  const protocol::LeaseRef warm{9, 1, 0};
  master_.Send(protocol::Message(PointLeaseOf(warm, gathering, 0, 10)));
  ASSERT_TRUE(WaitResult(warm, *agent));

  // Each of job 1's leases gathers at each of its points with 16384 rays (seconds of work), far
  // longer than the agent needs to read the rest of the burst, so none can finish before the
  // Cancel is read.
  std::vector<Outgoing> burst;
  const size_t points = std::min<size_t>(gathering.work.points.size(), 200);
  for (uint64_t piece = 1; piece <= 5; ++piece) {
    protocol::PointLeaseMsg lease = PointLeaseOf({1, piece, 0}, gathering, 0, points);
    lease.gather.assign(points, 1);
    lease.gather_rays = 16384;
    burst.push_back(protocol::Message(lease));
  }
  burst.push_back(protocol::Message(protocol::CancelMsg{1}));
  const protocol::LeaseRef after{2, 1, 0};
  burst.push_back(protocol::Message(PointLeaseOf(after, gathering, 10, 20)));
  master_.Send(burst);

  ASSERT_TRUE(WaitResult(after, *agent));
  ASSERT_TRUE(agent->WaitForLog("job 1 ended on " + master_.address() + ": dropped 5"))
      << agent->Log();
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    const auto beats = r.All<protocol::HeartbeatMsg>();
    return !beats.empty() && beats.back().leases_held == 0;
  }));
  for (const auto& result : master_.Snapshot().All<protocol::PointResultMsg>()) {
    EXPECT_NE(result.lease.job_id, 1u) << "piece " << result.lease.batch_id;
  }
  EXPECT_TRUE(master_.Snapshot().All<protocol::LeaseReturnMsg>().empty());
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

// The LeaseReturn carrying `lease`, once the master has it.
std::optional<protocol::LeaseReturnMsg> WaitReturn(const FakeMaster& master,
                                                   const protocol::LeaseRef& lease) {
  std::optional<protocol::LeaseReturnMsg> found;
  master.WaitFor([&](const Record& r) {
    for (const auto& returned : r.All<protocol::LeaseReturnMsg>()) {
      if (std::find(returned.leases.begin(), returned.leases.end(), lease) !=
          returned.leases.end()) {
        found = returned;
      }
    }
    return found.has_value();
  });
  return found;
}

TEST_F(AgentPointsTest, AContextTheMasterLacksOrADrainReturnsThePointLease) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  DisplayStep unknown = steps_[0];
  unknown.hash = protocol::HashScene(std::vector<uint8_t>{1, 2, 3});  // never added to the master
  const protocol::LeaseRef lacking{4, 1, 0};
  master_.Send(protocol::Message(PointLeaseOf(lacking, unknown, 0, 10)));
  const std::optional<protocol::LeaseReturnMsg> unavailable = WaitReturn(master_, lacking);
  ASSERT_TRUE(unavailable) << agent->Log();
  EXPECT_EQ(unavailable->reason, protocol::LeaseReturnReason::kSceneUnavailable);

  const protocol::LeaseRef drained{4, 2, 0};
  master_.Send({protocol::Message(protocol::DrainMsg{protocol::DrainMode::kFinishLeases, false}),
                protocol::Message(PointLeaseOf(drained, steps_[0], 0, 10))});
  const std::optional<protocol::LeaseReturnMsg> draining = WaitReturn(master_, drained);
  ASSERT_TRUE(draining) << agent->Log();
  EXPECT_EQ(draining->reason, protocol::LeaseReturnReason::kDraining);
  EXPECT_TRUE(master_.Snapshot().All<protocol::PointResultMsg>().empty());
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentPointsTest, ARevokedPointLeaseNotStartedIsDropped) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  const DisplayStep& gathering = steps_[1];
  const protocol::LeaseRef warm{5, 100, 0};
  master_.Send(protocol::Message(PointLeaseOf(warm, gathering, 0, 10)));
  ASSERT_TRUE(WaitResult(warm, *agent));
  // The agent's one worker takes the first lease; the second waits behind it when the revoke,
  // read in the same burst, drops it.
  const size_t points = std::min<size_t>(gathering.work.points.size(), 100);
  protocol::PointLeaseMsg first = PointLeaseOf({5, 1, 0}, gathering, 0, points);
  first.gather.assign(points, 1);
  first.gather_rays = 4096;
  const protocol::LeaseRef second{5, 2, 0};
  master_.Send({protocol::Message(first),
                protocol::Message(PointLeaseOf(second, gathering, 0, points)),
                protocol::Message(protocol::LeaseRevokeMsg{{second}})});
  ASSERT_TRUE(WaitResult(first.lease, *agent));
  ASSERT_TRUE(agent->WaitForLog("took back 1 of our point leases not started yet")) << agent->Log();
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    const auto beats = r.All<protocol::HeartbeatMsg>();
    return !beats.empty() && beats.back().leases_held == 0;
  }));
  for (const auto& result : master_.Snapshot().All<protocol::PointResultMsg>()) {
    EXPECT_NE(result.lease, second);
  }
  EXPECT_TRUE(master_.Snapshot().All<protocol::LeaseReturnMsg>().empty());
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

}  // namespace
}  // namespace radfarm::agent::testing
