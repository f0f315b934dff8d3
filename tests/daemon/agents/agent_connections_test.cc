// AgentConnections in-process (tests/daemon/master_parts.h, fake_agent.h): who is admitted, and
// where an agent's leases go when it disconnects or falls silent past agent_timeout_ms on the
// fake clock.
#include "daemon/agents/agent_connections.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "tests/daemon/agents/fake_agent.h"
#include "tests/daemon/master_parts.h"

namespace radfarm::daemon::fakes {
namespace {

scheduler::SchedulerCounters CountersOf(MasterParts& master, uint64_t job) {
  RunningJob* runner = master.jobs().FindRunner(job);
  EXPECT_NE(runner, nullptr);
  return runner ? runner->scheduler().counters(master.clock().Now())
                : scheduler::SchedulerCounters{};
}

TEST(AgentConnectionsTest, AnAgentWithTheFarmSecretIsAdmittedAndListed) {
  MasterParts master;
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  ASSERT_TRUE(agent.Connect().ok());
  // The master counts it once the proof checks; the agent is in once the Welcome reaches it.
  ASSERT_TRUE(
      master.RunUntil([&] { return master.agents().active() == 1 && agent.authenticated(); }));
  EXPECT_EQ(master.agents().Available().size(), 1u);

  ControlRequest list;
  list.command = ControlCommand::kAgents;
  const ControlResponse answer = master.Request(list);
  ASSERT_EQ(answer.body["agents"].size(), 1u) << answer.body.dump();
  EXPECT_EQ(answer.body["agents"][0]["name"], "box-1");
}

// `agents` listed 0 results for the agent that had computed a whole job: the count came from the
// running jobs' schedulers, which go when their job ends. It is the connection's now.
TEST(AgentConnectionsTest, AgentsCountsTheResultsOfAJobThatHasEnded) {
  MasterParts master;
  const uint64_t job = master.Submit(200000);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", true);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] {
    // No phase: neither starting, nor running rounds, nor drawing its display.
    return agent.results_sent() > 0 && master.jobs().PhaseOf(job).empty();
  }));
  ASSERT_EQ(master.StateOf(job), "done");

  ControlRequest list;
  list.command = ControlCommand::kAgents;
  const ControlResponse answer = master.Request(list);
  ASSERT_EQ(answer.body["agents"].size(), 1u) << answer.body.dump();
  const uint64_t results = answer.body["agents"][0]["results"].get<uint64_t>();
  // The one agent computed every batch the job accepted.
  EXPECT_GT(results, 0u);
  EXPECT_EQ(results, master.jobs().batch_totals(master.clock().Now()).accepted);
}

TEST(AgentConnectionsTest, AnAgentWithAnotherSecretIsRefused) {
  MasterParts master;
  const protocol::FarmSecret other = protocol::FarmSecret::Generate().value();
  FakeAgent agent(master.loop(), master.agent_address(), other, "stranger", true);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return agent.closed(); }));
  EXPECT_FALSE(agent.authenticated());
  EXPECT_EQ(master.agents().active(), 0u);
  EXPECT_TRUE(master.agents().Authenticated().empty());
}

TEST(AgentConnectionsTest, ADisconnectedAgentsLeasesAreLeasedToTheNextAgent) {
  MasterParts master;
  const uint64_t job = master.Submit(0);
  FakeAgent silent(master.loop(), master.agent_address(), master.secret(), "silent", false);
  ASSERT_TRUE(silent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return !silent.held().empty(); }));
  const std::set<BatchKey> lost = silent.held();
  const uint32_t round = std::get<1>(*lost.begin());

  silent.Drop();
  ASSERT_TRUE(master.RunUntil([&] { return master.agents().Authenticated().empty(); }));
  EXPECT_EQ(CountersOf(master, job).batches_leased, 0u);
  EXPECT_GE(CountersOf(master, job).leases_requeued, lost.size());

  FakeAgent next(master.loop(), master.agent_address(), master.secret(), "next", true);
  ASSERT_TRUE(next.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] {
    return std::includes(next.leased().begin(), next.leased().end(), lost.begin(), lost.end());
  }));
  // With the lost batches answered, the round they belonged to completes.
  ASSERT_TRUE(master.RunUntil([&] {
    RunningJob* runner = master.jobs().FindRunner(job);
    return runner && runner->totals().round > round;
  }));
}

TEST(AgentConnectionsTest, AnAgentSilentPastTheTimeoutLosesItsLeasesOnTheClocksWord) {
  MasterParts master;
  const uint64_t job = master.Submit(0);
  FakeAgent silent(master.loop(), master.agent_address(), master.secret(), "silent", false);
  ASSERT_TRUE(silent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return !silent.held().empty(); }));
  const uint64_t held = CountersOf(master, job).batches_leased;
  ASSERT_GT(held, 0u);

  // Exactly at the timeout it is still heard from.
  master.clock().Advance(std::chrono::milliseconds(master.config().agent_timeout_ms));
  master.agents().Heartbeat();
  EXPECT_EQ(master.agents().active(), 1u);
  EXPECT_EQ(CountersOf(master, job).batches_leased, held);

  // A millisecond later it is stale: no work, and its leases are queued for other agents.
  master.clock().Advance(std::chrono::milliseconds(1));
  master.agents().Heartbeat();
  EXPECT_EQ(master.agents().active(), 0u);
  EXPECT_TRUE(master.agents().Available().empty());
  EXPECT_EQ(CountersOf(master, job).batches_leased, 0u);
  EXPECT_GE(CountersOf(master, job).leases_requeued, held);
  EXPECT_FALSE(silent.closed());  // stale, not closed: it gets work again once it speaks
}

TEST(AgentConnectionsTest, AStaleAgentThatSpeaksAgainGetsWorkAgain) {
  MasterParts master;
  const uint64_t job = master.Submit(0);
  FakeAgent agent(master.loop(), master.agent_address(), master.secret(), "box-1", false);
  ASSERT_TRUE(agent.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return !agent.held().empty(); }));
  master.clock().Advance(std::chrono::milliseconds(master.config().agent_timeout_ms + 1));
  master.agents().Heartbeat();
  ASSERT_EQ(master.agents().active(), 0u);
  const uint64_t received = agent.batches_received();

  agent.SendHeartbeat();
  ASSERT_TRUE(master.RunUntil([&] { return agent.batches_received() > received; }));
  EXPECT_EQ(master.agents().active(), 1u);
  EXPECT_GT(CountersOf(master, job).batches_leased, 0u);
}

// One credential took every --max-agents place (60 connections under one enrolled name), and
// real agents were refused. A name now has at most max_connections_per_agent connections; the
// rest are refused after their handshake, told why, and another name still gets in.
TEST(AgentConnectionsTest, OneNameGetsAtMostItsConnectionsAndAnotherNameStillGetsIn) {
  MasterConfig config = TestMasterConfig();
  config.max_agents = 4;
  MasterParts master(config);
  std::vector<std::unique_ptr<FakeAgent>> one_name;
  for (int i = 0; i < 6; ++i) {
    one_name.push_back(std::make_unique<FakeAgent>(master.loop(), master.agent_address(),
                                                   master.secret(), "one-key", false));
    ASSERT_TRUE(one_name.back()->Connect().ok());
    // One at a time, so that which ones stay is known.
    ASSERT_TRUE(master.RunUntil(
        [&] { return one_name.back()->authenticated() || one_name.back()->closed(); }));
  }
  ASSERT_TRUE(master.RunUntil([&] {
    return std::count_if(one_name.begin(), one_name.end(),
                         [](const auto& a) { return a->closed(); }) == 4;
  }));
  for (size_t i = 0; i < one_name.size(); ++i) {
    if (i < 2) {
      EXPECT_FALSE(one_name[i]->closed()) << i;
    } else {
      EXPECT_EQ(one_name[i]->closed_reason(),
                "agent one-key already has 2 connections (--max-connections-per-agent)")
          << i;
    }
  }
  EXPECT_EQ(master.agents().doors().refused_per_agent, 4u);
  EXPECT_EQ(master.agents().active(), 2u);

  FakeAgent other(master.loop(), master.agent_address(), master.secret(), "other", true);
  ASSERT_TRUE(other.Connect().ok());
  ASSERT_TRUE(master.RunUntil([&] { return master.agents().active() == 3; }));
  EXPECT_FALSE(other.closed());
}

}  // namespace
}  // namespace radfarm::daemon::fakes
