// The real radfarm-agent against the fake master: batches, scenes and cancels.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <filesystem>

#include "codec/patch_scene_codec.h"
#include "protocol/batch_convert.h"
#include "protocol/frame_codec.h"
#include "protocol/scene_transfer.h"
#include "tests/agent/agent_process.h"
#include "tests/agent/fake_master.h"
#include "tests/agent/test_farm.h"

namespace radfarm::agent::testing {
namespace {

// A fake master with one scene, a key file, and a way to start agents against them.
class AgentWorkTest : public ::testing::Test {
 protected:
  explicit AgentWorkTest(int box = 3) : AgentWorkTest(BoxScene(box)) {}
  explicit AgentWorkTest(PatchScene scene)
      : scene_(std::move(scene)),
        blob_(codec::EncodePatchScene(scene_)),
        hash_(protocol::HashScene(blob_)),
        secret_(TestSecret(0x5a)),
        master_(secret_, Heartbeats(250, true)) {
    WriteSecretFile(dir_.File("key"), secret_);
    master_.AddScene(blob_);
  }

  std::unique_ptr<AgentProcess> StartAgent(unsigned threads, std::vector<std::string> extra = {}) {
    // Counted before the agent starts: it may authenticate before a later snapshot.
    const int connections = master_.Snapshot().authenticated + 1;
    auto agent = std::make_unique<AgentProcess>(
        AgentArgs(master_.address(), dir_.File("key"), threads, std::move(extra)));
    EXPECT_TRUE(master_.WaitFor([&](const Record& r) {
      return r.authenticated >= connections && r.open == 1;
    })) << agent->Log();
    EXPECT_TRUE(agent->WaitForLog("connected to " + master_.address())) << agent->Log();
    return agent;
  }

  protocol::AssignedBatch Assign(const TestJob& job, uint64_t batch, uint32_t shooter,
                                 uint64_t first_ray, uint32_t rays) {
    return Assignment(job, blob_, scene_, batch, shooter, first_ray, rays);
  }

  // Waits for the result of `lease`.
  std::optional<protocol::BatchOutcome> WaitResult(const protocol::LeaseRef& lease,
                                                   const AgentProcess& agent) {
    std::optional<protocol::BatchOutcome> found;
    const bool got = master_.WaitFor([&](const Record& r) {
      for (const auto& result : r.results) {
        if (result.lease == lease) found = result;
      }
      return found.has_value();
    });
    EXPECT_TRUE(got) << "no result for job " << lease.job_id << " batch " << lease.batch_id << "\n"
                     << agent.Log();
    return found;
  }

  ScratchDir dir_;
  PatchScene scene_;
  std::vector<uint8_t> blob_;
  protocol::SceneHash hash_;
  protocol::FarmSecret secret_;
  FakeMaster master_;
};

// Protocol version 2: many batches in one LeaseAssignment come back in one LeaseResult, each
// result equal to that batch computed alone.
TEST_F(AgentWorkTest, AMultiBatchLeaseIsAnsweredInOneFrameWithSingleBatchResults) {
  std::unique_ptr<AgentProcess> agent = StartAgent(2);
  const TestJob job = Job(4, SamplerKind::kSobol, 11);
  std::vector<protocol::AssignedBatch> batches;
  for (uint32_t k = 0; k < 40; ++k) {
    batches.push_back(Assign(job, 100 + k, /*shooter=*/k % 54, /*first_ray=*/1000 * k, 170 + k));
  }
  master_.Send(LeaseOf(batches));
  std::optional<protocol::LeaseResultMsg> frame;
  ASSERT_TRUE(master_.WaitFor([&](const Record& r) {
    const auto frames = r.All<protocol::LeaseResultMsg>();
    if (!frames.empty()) frame = frames.front();
    return frame.has_value();
  })) << agent->Log();
  ASSERT_EQ(frame->results.size(), batches.size());  // all in the one frame
  for (const protocol::AssignedBatch& batch : batches) {
    const auto found = std::find_if(frame->results.begin(), frame->results.end(),
                                    [&](const auto& r) { return r.lease == batch.lease; });
    ASSERT_NE(found, frame->results.end()) << "batch " << batch.lease.batch_id;
    EXPECT_EQ(protocol::ToBatchResult(*found), RunLocally(scene_, batch))
        << "batch " << batch.lease.batch_id;
  }
  EXPECT_EQ(master_.Snapshot().All<protocol::LeaseResultMsg>().size(), 1u);
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

// A LeaseRevoke right behind the lease: the agent's one thread has not reached the last batch
// (each takes tens of ms), so it drops it and answers the others without it.
TEST_F(AgentWorkTest, ARevokedBatchNotStartedIsLeftOutOfTheLeaseResult) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  const TestJob job = Job(5, SamplerKind::kSobol, 12);
  std::vector<protocol::AssignedBatch> batches;
  for (uint32_t k = 0; k < 6; ++k) {
    batches.push_back(Assign(job, 200 + k, /*shooter=*/k, /*first_ray=*/0, 200000));
  }
  master_.Send({LeaseOf(batches), protocol::LeaseRevokeMsg{{batches.back().lease}}});
  std::optional<protocol::LeaseResultMsg> frame;
  ASSERT_TRUE(master_.WaitFor([&](const Record& r) {
    const auto frames = r.All<protocol::LeaseResultMsg>();
    if (!frames.empty()) frame = frames.front();
    return frame.has_value();
  })) << agent->Log();
  ASSERT_EQ(frame->results.size(), batches.size() - 1) << agent->Log();
  for (size_t k = 0; k + 1 < batches.size(); ++k) {
    EXPECT_EQ(frame->results[k].lease, batches[k].lease);
    EXPECT_EQ(protocol::ToBatchResult(frame->results[k]), RunLocally(scene_, batches[k]));
  }
  EXPECT_TRUE(agent->WaitForLog("took back 1 of our batches")) << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentWorkTest, ResultsEqualBatchTracerOnTheSameBatchBitForBit) {
  std::unique_ptr<AgentProcess> agent = StartAgent(2);
  const std::vector<TestJob> jobs = {Job(1, SamplerKind::kSobol, 3),
                                     Job(2, SamplerKind::kRandom, 4),
                                     Job(3, SamplerKind::kGrid, 5, 7.5)};
  std::vector<protocol::AssignedBatch> assignments;
  for (const TestJob& job : jobs) {
    // The grid's shot is 12 x 48 = 576 rays at 7.5 degrees: its batches must lie inside it.
    const bool grid = job.sampler == SamplerKind::kGrid;
    assignments.push_back(Assign(job, 10, /*shooter=*/5, /*first_ray=*/0, grid ? 300 : 3000));
    assignments.push_back(
        Assign(job, 11, /*shooter=*/17, /*first_ray=*/grid ? 300 : 123456, grid ? 276 : 2000));
  }
  master_.Send(std::vector<Outgoing>(assignments.begin(), assignments.end()));
  for (const auto& assignment : assignments) {
    std::optional<protocol::BatchOutcome> result = WaitResult(assignment.lease, *agent);
    ASSERT_TRUE(result);
    EXPECT_EQ(protocol::ToBatchResult(*result), RunLocally(scene_, assignment))
        << "job " << assignment.lease.job_id << " batch " << assignment.lease.batch_id;
    EXPECT_GE(result->compute_seconds, 0);
  }
  EXPECT_EQ(master_.Snapshot().fetches.at(hash_), 1);  // one fetch served all six leases
  // Heartbeats now report a measured throughput.
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    const auto beats = r.All<protocol::HeartbeatMsg>();
    return !beats.empty() && beats.back().rays_per_second > 0;
  })) << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentWorkTest, CancelDropsTheJobsQueuedAndRunningWork) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  // Warm the scene first, so job 1's leases are queued behind a busy worker, not waiting for it.
  const auto warm = Assign(Job(9), 1, 0, 0, 100);
  master_.Send(warm);
  ASSERT_TRUE(WaitResult(warm.lease, *agent));

  // Each of job 1's batches takes far longer than the agent needs to read the rest of the burst,
  // so none can finish before the Cancel is read.
  std::vector<Outgoing> burst;
  for (uint64_t batch = 1; batch <= 20; ++batch) {
    burst.push_back(Assign(Job(1), batch, static_cast<uint32_t>(batch), 0, 2000000));
  }
  burst.push_back(protocol::CancelMsg{1});
  const auto after = Assign(Job(2), 1, 3, 0, 1000);
  burst.push_back(after);
  master_.Send(burst);

  // Without the cancel, job 1's twenty batches would all run, and be answered, before job 2's.
  ASSERT_TRUE(WaitResult(after.lease, *agent));
  ASSERT_TRUE(agent->WaitForLog("job 1 ended on " + master_.address() + ": dropped 20"))
      << agent->Log();
  // Heartbeats confirm nothing is held any more; no result of job 1 ever came.
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    const auto beats = r.All<protocol::HeartbeatMsg>();
    return !beats.empty() && beats.back().leases_held == 0;
  }));
  for (const auto& result : master_.Snapshot().results) {
    EXPECT_NE(result.lease.job_id, 1u) << "batch " << result.lease.batch_id;
  }
  EXPECT_TRUE(master_.Snapshot().All<protocol::LeaseReturnMsg>().empty());
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentWorkTest, ALostConnectionDropsEveryLeaseAndDiscardsTheirResults) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  // One batch long enough to be still running when the connection goes, one queued behind it.
  const auto running = Assign(Job(1), 1, 2, 0, kLongBatchRays);
  const auto queued = Assign(Job(1), 2, 3, 0, 1000);
  master_.Send({running, queued});
  ASSERT_TRUE(agent->WaitForLog("ready, ")) << agent->Log();
  master_.Drop();
  ASSERT_TRUE(agent->WaitForLog("lost the connection to " + master_.address())) << agent->Log();
  EXPECT_NE(agent->Log().find("dropped 2 leases"), std::string::npos) << agent->Log();
  ASSERT_TRUE(master_.WaitFor([](const Record& r) { return r.authenticated == 2 && r.open == 1; }))
      << agent->Log();
  // The running batch ends on the new connection's watch: its result is not sent there.
  ASSERT_TRUE(agent->WaitForLog("discarded the result of a lease no longer held")) << agent->Log();
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    const auto beats = r.All<protocol::HeartbeatMsg>();
    return !beats.empty() && beats.back().leases_held == 0;
  }));
  EXPECT_TRUE(master_.Snapshot().results.empty()) << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentWorkTest, AnUnknownSceneReturnsItsLeasesAsSceneUnavailable) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  const std::vector<uint8_t> other = codec::EncodePatchScene(BoxScene(2));  // not on the master
  auto a = Assignment(Job(4), other, BoxScene(2), 1, 0, 0, 100);
  auto b = Assignment(Job(4), other, BoxScene(2), 2, 1, 0, 100);
  master_.Send({a, b});
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    size_t returned = 0;
    for (const auto& back : r.All<protocol::LeaseReturnMsg>()) returned += back.leases.size();
    return returned == 2;
  })) << agent->Log();
  for (const auto& back : master_.Snapshot().All<protocol::LeaseReturnMsg>()) {
    EXPECT_EQ(back.reason, protocol::LeaseReturnReason::kSceneUnavailable);
  }
  EXPECT_TRUE(master_.Snapshot().results.empty());
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentWorkTest, APatchCountMismatchReturnsTheLeaseAsFailed) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  auto wrong = Assign(Job(6), 1, 0, 0, 100);
  wrong.patch_count += 1;
  master_.Send(wrong);
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    return !r.All<protocol::LeaseReturnMsg>().empty();
  })) << agent->Log();
  const auto back = master_.Snapshot().All<protocol::LeaseReturnMsg>().at(0);
  EXPECT_EQ(back.reason, protocol::LeaseReturnReason::kFailed);
  EXPECT_EQ(back.leases, std::vector<protocol::LeaseRef>{wrong.lease});
  EXPECT_NE(agent->Log().find("the assignment says"), std::string::npos) << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentWorkTest, AGridBatchBeyondItsShotIsReturnedAsFailed) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  const auto beyond = Assign(Job(5, SamplerKind::kGrid, 1, 7.5), 1, 0, 500, 100);  // 576 a shot
  master_.Send(beyond);
  ASSERT_TRUE(master_.WaitFor([](const Record& r) {
    return !r.All<protocol::LeaseReturnMsg>().empty();
  })) << agent->Log();
  const auto back = master_.Snapshot().All<protocol::LeaseReturnMsg>().at(0);
  EXPECT_EQ(back.reason, protocol::LeaseReturnReason::kFailed);
  EXPECT_EQ(back.leases, std::vector<protocol::LeaseRef>{beyond.lease});
  EXPECT_NE(agent->Log().find("beyond the grid's 576 rays per shot"), std::string::npos)
      << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

TEST_F(AgentWorkTest, TheStateDirectoryKeepsTheSceneForARestartedAgent) {
  const std::string state = dir_.File("state");
  const std::string file = state + "/scenes/" + protocol::HashToHex(hash_) + ".scene";
  {
    std::unique_ptr<AgentProcess> agent = StartAgent(1, {"--state-dir", state});
    const auto first = Assign(Job(1), 1, 2, 0, 500);
    master_.Send(first);
    ASSERT_TRUE(WaitResult(first.lease, *agent));
    const auto second = Assign(Job(1), 2, 3, 0, 500);
    master_.Send(second);
    ASSERT_TRUE(WaitResult(second.lease, *agent));
    EXPECT_EQ(master_.Snapshot().fetches.at(hash_), 1);
    // The fetched scene is put in place after it is ready (SceneSupply::OnPrepared).
    ASSERT_TRUE(agent->WaitForLog("saved as " + file)) << agent->Log();
    agent->Signal(SIGTERM);
    ASSERT_EQ(agent->WaitExit(), 0) << agent->Log();
  }
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_EQ(ReadTextFile(file), std::string(blob_.begin(), blob_.end()));

  std::unique_ptr<AgentProcess> restarted = StartAgent(1, {"--state-dir", state});
  const auto third = Assign(Job(1), 3, 4, 0, 500);
  master_.Send(third);
  std::optional<protocol::BatchOutcome> result = WaitResult(third.lease, *restarted);
  ASSERT_TRUE(result);
  EXPECT_EQ(protocol::ToBatchResult(*result), RunLocally(scene_, third));
  EXPECT_EQ(master_.Snapshot().fetches.at(hash_), 1) << "the restarted agent fetched again";
  restarted->Signal(SIGTERM);
  EXPECT_EQ(restarted->WaitExit(), 0) << restarted->Log();
}

TEST_F(AgentWorkTest, ADamagedSceneFileIsDeletedAndFetchedAgain) {
  const std::string state = dir_.File("state");
  std::filesystem::create_directories(state + "/scenes");
  const std::string file = state + "/scenes/" + protocol::HashToHex(hash_) + ".scene";
  std::string damaged(blob_.begin(), blob_.end());
  damaged[damaged.size() / 2] ^= 1;
  WriteTextFile(file, damaged);

  std::unique_ptr<AgentProcess> agent = StartAgent(1, {"--state-dir", state});
  const auto lease = Assign(Job(1), 1, 2, 0, 500);
  master_.Send(lease);
  std::optional<protocol::BatchOutcome> result = WaitResult(lease.lease, *agent);
  ASSERT_TRUE(result);
  EXPECT_EQ(protocol::ToBatchResult(*result), RunLocally(scene_, lease));
  EXPECT_EQ(master_.Snapshot().fetches.at(hash_), 1);
  // The fetched scene is put in place after it is ready (SceneSupply::OnPrepared).
  ASSERT_TRUE(agent->WaitForLog("saved as " + file)) << agent->Log();
  EXPECT_EQ(ReadTextFile(file), std::string(blob_.begin(), blob_.end()));
  EXPECT_NE(agent->Log().find("damaged file"), std::string::npos) << agent->Log();
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

// A scene of several chunks goes through the pipelined fetch.
class AgentBigSceneTest : public AgentWorkTest {
 protected:
  AgentBigSceneTest() : AgentWorkTest(VariedBoxScene(kBigBox)) {}
};

TEST_F(AgentBigSceneTest, ASceneOfSeveralChunksIsFetchedOnce) {
  const uint64_t compressed = protocol::PackScene(blob_).compressed.size();
  ASSERT_GT(compressed, 2 * protocol::kMaxSceneChunkBytes);
  std::unique_ptr<AgentProcess> agent = StartAgent(2);
  std::vector<Outgoing> leases;
  for (uint64_t batch = 1; batch <= 4; ++batch) {
    leases.push_back(Assign(Job(1), batch, static_cast<uint32_t>(batch * 1000), 0, 500));
  }
  master_.Send(leases);
  for (const auto& message : leases) {
    const auto& assignment = std::get<protocol::AssignedBatch>(message);
    std::optional<protocol::BatchOutcome> result = WaitResult(assignment.lease, *agent);
    ASSERT_TRUE(result);
    EXPECT_EQ(protocol::ToBatchResult(*result), RunLocally(scene_, assignment));
  }
  const Record seen = master_.Snapshot();
  EXPECT_EQ(seen.fetches.at(hash_), 1);
  EXPECT_EQ(static_cast<uint64_t>(seen.scene_requests),
            (compressed + protocol::kMaxSceneChunkBytes - 1) / protocol::kMaxSceneChunkBytes);
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

// A lease frame's results go out together, except that results filling a frame go out as soon as
// they are done: a big scene's long batch has a result of hundreds of KB, and holding them for the
// frame's last batch piled them up in the agent's memory. Here the first batch's result must
// reach the master while the second, 50 million rays, still runs: the job is then cancelled, and
// the second's result never comes (held for the frame, both would come together after it).
class AgentManyPatchesTest : public AgentWorkTest {
 protected:
  AgentManyPatchesTest() : AgentWorkTest(BoxScene(110)) {}  // 72,600 patches
};

TEST_F(AgentManyPatchesTest, AResultFillingAFrameGoesOutBeforeTheLeasesLastBatch) {
  std::unique_ptr<AgentProcess> agent = StartAgent(1);
  const TestJob job = Job(3);
  const auto first = Assign(job, 1, /*shooter=*/100, 0, 4'000'000);
  const auto last = Assign(job, 2, /*shooter=*/200, 0, kLongBatchRays);
  master_.Send(LeaseOf({first, last}));
  std::optional<protocol::BatchOutcome> result = WaitResult(first.lease, *agent);
  ASSERT_TRUE(result);
  ASSERT_GT(protocol::ResultFrameCost(*result, protocol::kProtocolVersion),
            protocol::kResultFrameBytes);  // it fills a frame alone
  EXPECT_EQ(protocol::ToBatchResult(*result), RunLocally(scene_, first));
  master_.Send(protocol::CancelMsg{job.job_id});
  ASSERT_TRUE(agent->WaitForLog("job 3 ended on " + master_.address() + ": dropped 1"))
      << agent->Log();
  // The running batch finishes, and its result is dropped rather than sent.
  ASSERT_TRUE(agent->WaitForLog("discarded the result of a lease no longer held")) << agent->Log();
  for (const auto& sent : master_.Snapshot().results) {
    EXPECT_NE(sent.lease, last.lease) << agent->Log();
  }
  agent->Signal(SIGTERM);
  EXPECT_EQ(agent->WaitExit(), 0) << agent->Log();
}

}  // namespace
}  // namespace radfarm::agent::testing
