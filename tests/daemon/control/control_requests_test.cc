// ControlRequests in-process (tests/daemon/master_parts.h): the answers of docs/CONTROL.md for
// jobs that do not exist, state changes a job's state refuses, pause and resume, bad submissions
// and a stopping master, read back through the same requests.
#include "daemon/control/control_requests.h"

#include <gtest/gtest.h>

#include <limits>

#include "tests/daemon/master_parts.h"

namespace radfarm::daemon::fakes {
namespace {

std::string CodeOf(const ControlResponse& answer) { return answer.body.value("code", ""); }

// No job starts: what the control socket does to a queued job is all that happens to it.
MasterConfig NothingStarts() {
  MasterConfig config = TestMasterConfig();
  config.max_running_jobs = 0;
  return config;
}

TEST(ControlRequestsTest, EveryRequestForAJobThatDoesNotExistIsNotFound) {
  MasterParts master;
  for (ControlCommand command :
       {ControlCommand::kStatus, ControlCommand::kCancel, ControlCommand::kPause,
        ControlCommand::kResume, ControlCommand::kFetch, ControlCommand::kLog}) {
    const ControlResponse answer = master.Request(command, 42);
    EXPECT_FALSE(answer.body["ok"].get<bool>()) << answer.body.dump();
    EXPECT_EQ(CodeOf(answer), "not_found") << answer.body.dump();
    EXPECT_NE(answer.body.value("error", "").find("42"), std::string::npos) << answer.body.dump();
  }
}

TEST(ControlRequestsTest, AnIdBeyondTheStoresRangeNamesNoJob) {
  MasterParts master;
  const uint64_t id = uint64_t(std::numeric_limits<int64_t>::max()) + 1;
  const ControlResponse answer = master.Request(ControlCommand::kStatus, id);
  EXPECT_EQ(CodeOf(answer), "not_found") << answer.body.dump();
  EXPECT_NE(answer.body.value("error", "").find(std::to_string(id)), std::string::npos);
}

TEST(ControlRequestsTest, APausedJobResumesIntoTheQueueAndRefusesASecondPause) {
  MasterParts master(NothingStarts());
  const uint64_t id = master.Submit(0);
  ASSERT_NE(id, 0u);
  EXPECT_EQ(master.StateOf(id), "queued");

  const ControlResponse paused = master.Request(ControlCommand::kPause, id);
  ASSERT_TRUE(paused.body["ok"].get<bool>()) << paused.body.dump();
  EXPECT_EQ(paused.body["job"]["state"], "paused");
  EXPECT_EQ(master.StateOf(id), "paused");

  const ControlResponse again = master.Request(ControlCommand::kPause, id);
  EXPECT_EQ(CodeOf(again), "invalid_state") << again.body.dump();
  EXPECT_EQ(master.StateOf(id), "paused");

  const ControlResponse resumed = master.Request(ControlCommand::kResume, id);
  ASSERT_TRUE(resumed.body["ok"].get<bool>()) << resumed.body.dump();
  EXPECT_EQ(master.StateOf(id), "queued");
}

TEST(ControlRequestsTest, ACancelledJobCanNeitherResumeNorBeCancelledAgain) {
  MasterParts master(NothingStarts());
  const uint64_t id = master.Submit(0);
  ASSERT_TRUE(master.Request(ControlCommand::kCancel, id).body["ok"].get<bool>());
  EXPECT_EQ(master.StateOf(id), "cancelled");
  EXPECT_EQ(CodeOf(master.Request(ControlCommand::kResume, id)), "invalid_state");
  EXPECT_EQ(CodeOf(master.Request(ControlCommand::kCancel, id)), "invalid_state");
  EXPECT_EQ(master.StateOf(id), "cancelled");
}

TEST(ControlRequestsTest, ListAndLogShowTheSubmittedJobs) {
  MasterParts master(NothingStarts());
  const uint64_t first = master.Submit(0, 1);
  const uint64_t second = master.Submit(0, 2);
  ControlRequest list;
  list.command = ControlCommand::kList;
  const ControlResponse jobs = master.Request(list);
  ASSERT_TRUE(jobs.body["ok"].get<bool>());
  ASSERT_EQ(jobs.body["jobs"].size(), 2u);
  EXPECT_EQ(jobs.body["jobs"][0]["id"], first);
  EXPECT_EQ(jobs.body["jobs"][1]["id"], second);
  EXPECT_EQ(jobs.body["jobs"][1]["priority"], 2);

  const ControlResponse log = master.Request(ControlCommand::kLog, second);
  ASSERT_TRUE(log.body["ok"].get<bool>());
  ASSERT_FALSE(log.body["events"].empty());
  EXPECT_EQ(log.body["events"][0]["text"], "submitted");
}

TEST(ControlRequestsTest, ABundleThatDoesNotDecodeIsABadRequestAndStoresNothing) {
  MasterParts master;
  ControlRequest submit;
  submit.command = ControlCommand::kSubmit;
  submit.attachment = {1, 2, 3, 4};
  const ControlResponse answer = master.Request(submit);
  EXPECT_EQ(CodeOf(answer), "bad_request") << answer.body.dump();
  ControlRequest list;
  list.command = ControlCommand::kList;
  EXPECT_TRUE(master.Request(list).body["jobs"].empty());
}

TEST(ControlRequestsTest, FetchBeforeTheFirstCheckpointIsInvalidState) {
  MasterParts master(NothingStarts());
  const uint64_t id = master.Submit(0);
  const ControlResponse answer = master.Request(ControlCommand::kFetch, id);
  EXPECT_EQ(CodeOf(answer), "invalid_state") << answer.body.dump();
  EXPECT_TRUE(answer.attachment.empty());
}

TEST(ControlRequestsTest, AgentsEnrollAndRevokeByValidNamesOnly) {
  MasterParts master;
  ControlRequest enroll;
  enroll.command = ControlCommand::kEnrollAgent;
  enroll.name = "has space";
  EXPECT_EQ(CodeOf(master.Request(enroll)), "bad_request");

  ControlRequest revoke;
  revoke.command = ControlCommand::kRevokeAgent;
  revoke.name = "never-enrolled";
  EXPECT_EQ(CodeOf(master.Request(revoke)), "not_found");

  enroll.name = "render-01";
  const ControlResponse enrolled = master.Request(enroll);
  ASSERT_TRUE(enrolled.body["ok"].get<bool>()) << enrolled.body.dump();
  EXPECT_EQ(enrolled.body["key"].get<std::string>().size(), 64u);
  revoke.name = "render-01";
  const ControlResponse revoked = master.Request(revoke);
  ASSERT_TRUE(revoked.body["ok"].get<bool>()) << revoked.body.dump();
  EXPECT_EQ(revoked.body["closed"], 0);
}

TEST(ControlRequestsTest, AStoppingMasterAnswersEveryRequestWithAnError) {
  MasterParts master(NothingStarts());
  const uint64_t id = master.Submit(0);
  master.control().Stop();
  const ControlResponse answer = master.Request(ControlCommand::kStatus, id);
  EXPECT_EQ(CodeOf(answer), "internal");
  EXPECT_EQ(answer.body["error"], "the master is shutting down");
}

}  // namespace
}  // namespace radfarm::daemon::fakes
