// IdleMonitor on a real event loop with a simulated user and a fake CPU load: the agent's side
// (on_change) must hear "stop" on the first check after the user returns, and "go" again once
// the user has left.
#include "idle/idle_monitor.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "loop_test_util.h"

namespace radfarm::idle {
namespace {

using loop::EventLoop;
using loop::testing::ExpectClosesClean;
using loop::testing::RunUntil;
using std::chrono::milliseconds;
using std::chrono::minutes;
using std::chrono::seconds;

// What the simulated user and the fake load look like now; the sources read it.
struct SimulatedMachine {
  UserIdle user{UserIdle::State::kIdle, minutes(30), "fake"};
  std::optional<double> other_cpu = 0.05;
  int user_reads = 0;
  int cpu_reads = 0;
};

class FakeUser : public UserIdleSource {
 public:
  explicit FakeUser(SimulatedMachine& machine) : machine_(machine) {}
  UserIdle Read() override {
    ++machine_.user_reads;
    return machine_.user;
  }

 private:
  SimulatedMachine& machine_;
};

class FakeCpu : public CpuLoadSource {
 public:
  explicit FakeCpu(SimulatedMachine& machine) : machine_(machine) {}
  std::optional<double> OtherLoad() override {
    // Like ProcCpuLoad: the first reading is only a baseline.
    return machine_.cpu_reads++ == 0 ? std::nullopt : machine_.other_cpu;
  }
  std::string detail() const override { return "fake"; }

 private:
  SimulatedMachine& machine_;
};

IdleSources FakeSources(SimulatedMachine& machine) {
  return IdleSources{std::make_unique<FakeUser>(machine), std::make_unique<FakeCpu>(machine), [] {
                       return LocalTime{2, 12 * 60};
                     }};
}

IdlePolicy Policy() {
  IdleConfig config;
  config.user_idle_minutes = 0;  // the simulated user is idle as soon as it leaves
  config.max_other_cpu = 0.5;
  config.poll_seconds = 1;
  Result<IdlePolicy> policy = IdlePolicy::Create(config, HysteresisSettings{milliseconds(0), 0.8});
  EXPECT_TRUE(policy.ok()) << policy.error();
  return std::move(policy).value();
}

constexpr IdleMonitorTiming kFastTiming{milliseconds(2), milliseconds(1)};

TEST(IdleMonitorTest, SimulatedUserComesBackAndLeaves) {
  SimulatedMachine machine;
  std::vector<IdleDecision> changes;
  std::vector<int> reads_at_change;
  EventLoop loop;
  {
    IdleMonitor monitor(
        loop, Policy(), FakeSources(machine),
        [&](const IdleDecision& decision) {
          changes.push_back(decision);
          reads_at_change.push_back(machine.user_reads);
        },
        kFastTiming);
    EXPECT_FALSE(monitor.may_work());  // nothing measured yet
    monitor.Start();
    ASSERT_TRUE(RunUntil(loop, [&] { return changes.size() == 1; }));
    EXPECT_TRUE(changes[0].may_work) << changes[0].reason;
    EXPECT_TRUE(monitor.may_work());

    // The user comes back: the very next check says stop.
    machine.user = {UserIdle::State::kActive, seconds(0), "fake"};
    const int reads_before = machine.user_reads;
    ASSERT_TRUE(RunUntil(loop, [&] { return changes.size() == 2; }));
    EXPECT_FALSE(changes[1].may_work);
    EXPECT_EQ(changes[1].reason, "user active");
    EXPECT_EQ(reads_at_change[1], reads_before + 1);

    // The user leaves: work resumes.
    machine.user = {UserIdle::State::kIdle, seconds(0), "fake"};
    ASSERT_TRUE(RunUntil(loop, [&] { return changes.size() == 3; }));
    EXPECT_TRUE(changes[2].may_work);

    // Repeated identical answers are not reported again.
    const int reads = machine.user_reads;
    ASSERT_TRUE(RunUntil(loop, [&] { return machine.user_reads >= reads + 5; }));
    EXPECT_EQ(changes.size(), 3u);
    monitor.Stop();
  }
  ExpectClosesClean(loop);
}

TEST(IdleMonitorTest, OtherProcessesLoadStopsWork) {
  SimulatedMachine machine;
  machine.other_cpu = 0.9;  // a synthetic load from another process
  std::vector<IdleDecision> changes;
  EventLoop loop;
  {
    IdleMonitor monitor(
        loop, Policy(), FakeSources(machine),
        [&](const IdleDecision& decision) { changes.push_back(decision); }, kFastTiming);
    monitor.Start();
    ASSERT_TRUE(RunUntil(loop, [&] { return changes.size() == 1; }));
    EXPECT_FALSE(changes[0].may_work);
    EXPECT_EQ(changes[0].reason, "other processes use 90% of the CPUs (limit 50%)");
    EXPECT_GE(machine.cpu_reads, 2);  // decided on a measurement, not on the baseline
  }
  ExpectClosesClean(loop);
}

// The real sources (logind or "unknown", /proc/stat, the local clock) behind the monitor: it
// answers, and the answer is consistent with what it says.
TEST(IdleMonitorTest, SystemSourcesGiveAnAnswer) {
  IdleConfig config;
  config.user_idle_minutes = 0;
  config.max_other_cpu = 1.0;  // this machine's load is whatever other tests make it
  Result<IdlePolicy> policy = IdlePolicy::Create(config);
  ASSERT_TRUE(policy.ok()) << policy.error();
  std::vector<IdleDecision> changes;
  EventLoop loop;
  {
    IdleMonitor monitor(
        loop, std::move(policy).value(), SystemIdleSources(),
        [&](const IdleDecision& decision) { changes.push_back(decision); },
        IdleMonitorTiming{milliseconds(5), milliseconds(20)});
    monitor.Start();
    ASSERT_TRUE(RunUntil(loop, [&] { return !changes.empty(); }));
    const IdleDecision& first = changes[0];
    if (first.may_work) {
      EXPECT_EQ(first.reason.rfind("idle: ", 0), 0u) << first.reason;
    } else {
      EXPECT_EQ(first.reason, "user active");  // logind says someone is at this machine
    }
  }
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::idle
