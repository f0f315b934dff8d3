// The real radfarm-agent against the fake master: SIGTERM, Drain and --exit-when-idle.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>

#include "codec/patch_scene_codec.h"
#include "protocol/scene_transfer.h"
#include "tests/agent/agent_process.h"
#include "tests/agent/fake_master.h"
#include "tests/agent/test_farm.h"

namespace radfarm::agent::testing {
namespace {

class AgentShutdownTest : public ::testing::Test {
 protected:
  AgentShutdownTest()
      : scene_(BoxScene(3)), blob_(codec::EncodePatchScene(scene_)), secret_(TestSecret(0x6b)) {
    WriteSecretFile(dir_.File("key"), secret_);
    StartMaster({});
  }

  // A master that heartbeats every 250 ms and sends `after_welcome` to every agent that joins.
  void StartMaster(std::vector<Outgoing> after_welcome) {
    FakeMasterOptions options = Heartbeats(250, true);
    options.after_welcome = std::move(after_welcome);
    master_.reset();
    master_ = std::make_unique<FakeMaster>(secret_, options);
    master_->AddScene(blob_);
  }

  std::unique_ptr<AgentProcess> StartAgent(unsigned threads, std::vector<std::string> extra = {}) {
    auto agent = std::make_unique<AgentProcess>(
        AgentArgs(master_->address(), dir_.File("key"), threads, std::move(extra)));
    EXPECT_TRUE(master_->WaitFor([](const Record& r) { return r.open == 1; })) << agent->Log();
    EXPECT_TRUE(agent->WaitForLog("connected to " + master_->address())) << agent->Log();
    return agent;
  }

  // `count` leases of job 1, `rays` rays each.
  std::vector<protocol::AssignedBatch> Leases(int count, uint32_t rays) {
    std::vector<protocol::AssignedBatch> leases;
    for (int i = 1; i <= count; ++i) {
      leases.push_back(Assignment(Job(1), blob_, scene_, static_cast<uint64_t>(i),
                                  static_cast<uint32_t>(i), 0, rays));
    }
    return leases;
  }

  void Send(const std::vector<protocol::AssignedBatch>& leases) {
    master_->Send(std::vector<Outgoing>(leases.begin(), leases.end()));
  }

  // Waits until a heartbeat reports `held` leases.
  bool WaitHeld(uint32_t held) {
    return master_->WaitFor([held](const Record& r) {
      const auto beats = r.All<protocol::HeartbeatMsg>();
      return !beats.empty() && beats.back().leases_held == held;
    });
  }

  static std::vector<protocol::LeaseRef> Refs(const std::vector<protocol::AssignedBatch>& leases) {
    std::vector<protocol::LeaseRef> refs;
    for (const auto& lease : leases) refs.push_back(lease.lease);
    return refs;
  }

  // Every lease returned so far, sorted, with the reasons seen.
  std::vector<protocol::LeaseRef> Returned(protocol::LeaseReturnReason expected_reason) {
    std::vector<protocol::LeaseRef> refs;
    for (const auto& back : master_->Snapshot().All<protocol::LeaseReturnMsg>()) {
      EXPECT_EQ(back.reason, expected_reason);
      refs.insert(refs.end(), back.leases.begin(), back.leases.end());
    }
    std::sort(refs.begin(), refs.end(),
              [](const auto& a, const auto& b) { return a.batch_id < b.batch_id; });
    return refs;
  }

  void ExpectClosedWithShutdown() {
    const auto closes = master_->Snapshot().All<protocol::CloseMsg>();
    ASSERT_EQ(closes.size(), 1u);
    EXPECT_EQ(closes[0].code, protocol::CloseCode::kShutdown);
  }

  ScratchDir dir_;
  PatchScene scene_;
  std::vector<uint8_t> blob_;
  protocol::FarmSecret secret_;
  std::unique_ptr<FakeMaster> master_;
};

TEST_F(AgentShutdownTest, SigtermReturnsEveryLeaseEvenWithABatchStillRunning) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  // A batch far too long to finish, then two queued behind it.
  std::vector<protocol::AssignedBatch> leases = Leases(3, 1000);
  leases[0].ray_count = 4000000000u;
  Send(leases);
  ASSERT_TRUE(WaitHeld(3)) << agent->Log();
  ASSERT_TRUE(agent->WaitForLog("ready, ")) << agent->Log();  // the scene is in: the batch runs
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
  EXPECT_EQ(Returned(protocol::LeaseReturnReason::kDraining), Refs(leases));
  EXPECT_EQ(master_->Snapshot().All<protocol::LeaseReturnMsg>().size(), 1u);
  EXPECT_TRUE(master_->Snapshot().results.empty());
  ExpectClosedWithShutdown();
  EXPECT_NE(agent->Log().find("exiting without waiting for running batches"), std::string::npos)
      << agent->Log();
}

TEST_F(AgentShutdownTest, SigtermReturnsResultsHeldBySlowdown) {
  // --slowdown holds each computed result for 1e6 x its compute time: they are still held.
  std::unique_ptr<AgentProcess> agent = StartAgent(2, {"--slowdown", "1000000"});
  const std::vector<protocol::AssignedBatch> leases = Leases(3, 2000);
  Send(leases);
  ASSERT_TRUE(agent->WaitForLog("result held for", 3)) << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
  EXPECT_EQ(Returned(protocol::LeaseReturnReason::kDraining), Refs(leases));
  EXPECT_TRUE(master_->Snapshot().results.empty());
  ExpectClosedWithShutdown();
  // Nothing was running: the clean exit path.
  EXPECT_NE(agent->Log().find("INFO  agent: exited"), std::string::npos) << agent->Log();
}

TEST_F(AgentShutdownTest, DrainFinishLeasesWithExitSendsEveryResultThenCloses) {
  std::unique_ptr<AgentProcess> agent = StartAgent(2);
  const std::vector<protocol::AssignedBatch> leases = Leases(4, 5000);
  Send(leases);
  master_->Send(protocol::DrainMsg{protocol::DrainMode::kFinishLeases, /*exit_after=*/true});
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
  const Record seen = master_->Snapshot();
  EXPECT_EQ(seen.results.size(), 4u);
  EXPECT_TRUE(seen.All<protocol::LeaseReturnMsg>().empty());
  ExpectClosedWithShutdown();
  // The Close comes after the last result.
  EXPECT_TRUE(std::holds_alternative<protocol::CloseMsg>(seen.received.back()));
}

TEST_F(AgentShutdownTest, DrainReturnLeasesWithExitReturnsThemAndCloses) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1, {"--slowdown", "1000000"});
  std::vector<protocol::AssignedBatch> leases = Leases(3, 1000);
  Send(leases);
  ASSERT_TRUE(WaitHeld(3)) << agent->Log();
  master_->Send(protocol::DrainMsg{protocol::DrainMode::kReturnLeases, /*exit_after=*/true});
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
  EXPECT_EQ(Returned(protocol::LeaseReturnReason::kDraining), Refs(leases));
  ExpectClosedWithShutdown();
}

TEST_F(AgentShutdownTest, DrainWithoutExitRefusesNewLeasesAndStaysConnected) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  master_->Send(protocol::DrainMsg{protocol::DrainMode::kFinishLeases, /*exit_after=*/false});
  const std::vector<protocol::AssignedBatch> leases = Leases(2, 100);
  Send(leases);
  ASSERT_TRUE(master_->WaitFor([](const Record& r) {
    size_t returned = 0;
    for (const auto& back : r.All<protocol::LeaseReturnMsg>()) returned += back.leases.size();
    return returned == 2;
  })) << agent->Log();
  EXPECT_EQ(Returned(protocol::LeaseReturnReason::kDraining), Refs(leases));
  EXPECT_TRUE(agent->Running());
  EXPECT_EQ(master_->Snapshot().open, 1);
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

// The idle period counts from the agent's start, so it is long enough for the agent to connect
// first (a few milliseconds on loopback) even on a loaded machine.
TEST_F(AgentShutdownTest, ExitWhenIdleExitsOnceNothingIsHeld) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1, {"--exit-when-idle", "2"});
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
  ExpectClosedWithShutdown();
  EXPECT_NE(agent->Log().find("--exit-when-idle"), std::string::npos) << agent->Log();
}

TEST_F(AgentShutdownTest, ExitWhenIdleWaitsForHeldLeases) {
  // The lease comes with the Welcome, so the agent is never idle before it; --slowdown then holds
  // its result, and held results count as held leases.
  const std::vector<protocol::AssignedBatch> leases = Leases(1, 100);
  StartMaster({leases[0]});
  std::unique_ptr<AgentProcess> agent =
      StartAgent(1, {"--exit-when-idle", "1", "--slowdown", "1000000"});
  ASSERT_TRUE(agent->WaitForLog("result held for")) << agent->Log();
  // Three idle periods pass, in heartbeats (every 250 ms), while the lease is held; then Cancel
  // frees the agent.
  const size_t beats = master_->Snapshot().All<protocol::HeartbeatMsg>().size();
  ASSERT_TRUE(master_->WaitFor([beats](const Record& r) {
    return r.All<protocol::HeartbeatMsg>().size() >= beats + 12;
  })) << agent->Log();
  EXPECT_TRUE(agent->Running()) << agent->Log();
  master_->Send(protocol::CancelMsg{1});
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
  ExpectClosedWithShutdown();
}

// `--exit-when-idle 2` against an unreachable master still ran after 8 s, so a batch
// agent held its allocation until the walltime. Without a master the idle period runs too.
TEST_F(AgentShutdownTest, ExitWhenIdleExitsWhenNoMasterIsReachable) {
  const std::string gone = master_->address();
  master_.reset();  // nobody listens on its port any more
  AgentProcess agent(AgentArgs(gone, dir_.File("key"), 1, {"--exit-when-idle", "1"}));
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
  const std::string log = agent.Log();
  EXPECT_NE(log.find("no lease for 1 s (cannot connect to " + gone), std::string::npos) << log;
  EXPECT_NE(log.find("--exit-when-idle"), std::string::npos) << log;
  EXPECT_EQ(log.find("connected to " + gone + " as "), std::string::npos) << log;
}

// The master goes away while the agent holds a lease: the lease is dropped with the connection,
// and the idle period that starts then ends the agent although it never reconnects.
TEST_F(AgentShutdownTest, ExitWhenIdleExitsWhenTheMasterGoesAwayForGood) {
  const std::vector<protocol::AssignedBatch> leases = Leases(1, 100);
  StartMaster({leases[0]});
  const std::string address = master_->address();
  std::unique_ptr<AgentProcess> agent =
      StartAgent(1, {"--exit-when-idle", "1", "--slowdown", "1000000"});
  ASSERT_TRUE(agent->WaitForLog("result held for")) << agent->Log();
  master_.reset();
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
  const std::string log = agent->Log();
  EXPECT_NE(log.find("lost the connection to " + address), std::string::npos) << log;
  EXPECT_NE(log.find("no lease for 1 s ("), std::string::npos) << log;
}

}  // namespace
}  // namespace radfarm::agent::testing
