// The policy against a simulated user and a fake clock: each test drives samples by hand.
#include "idle/idle_policy.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "loop/log.h"

namespace radfarm::idle {
namespace {

using std::chrono::milliseconds;
using std::chrono::minutes;
using std::chrono::seconds;
using Clock = std::chrono::steady_clock;

UserIdle IdleFor(seconds idle) { return {UserIdle::State::kIdle, idle, "fake"}; }
UserIdle Active() { return {UserIdle::State::kActive, seconds(0), "fake"}; }
UserIdle Unknown() { return {UserIdle::State::kUnknown, seconds(0), "no system bus"}; }

// A simulated machine: the test moves its clock and changes its user and load.
struct FakeMachine {
  Clock::time_point now{};
  UserIdle user = IdleFor(minutes(60));
  std::optional<double> other_cpu = 0.0;
  LocalTime local{2, 12 * 60};  // Wednesday noon

  IdleSample Sample() const { return {now, user, other_cpu, local}; }
  void Advance(milliseconds step) {
    now += step;
    if (user.state == UserIdle::State::kIdle) {
      user.idle_for += std::chrono::duration_cast<seconds>(step);
    }
  }
};

IdlePolicy MakePolicy(IdleConfig config, HysteresisSettings hysteresis = {}) {
  Result<IdlePolicy> policy = IdlePolicy::Create(config, hysteresis);
  EXPECT_TRUE(policy.ok()) << policy.error();
  return std::move(policy).value();
}

IdleConfig Config() {
  IdleConfig config;
  config.user_idle_minutes = 10;
  config.max_other_cpu = 0.5;
  config.poll_seconds = 5;
  return config;
}

TEST(IdlePolicyTest, IdleMachineMayWorkAtOnce) {
  IdlePolicy policy = MakePolicy(Config());
  FakeMachine machine;
  const IdleDecision decision = policy.Decide(machine.Sample());
  EXPECT_TRUE(decision.may_work);
  EXPECT_EQ(decision.reason, "idle: user idle 60 min, other CPU 0%");
}

TEST(IdlePolicyTest, ReturningUserStopsWorkOnTheNextSample) {
  IdlePolicy policy = MakePolicy(Config());
  FakeMachine machine;
  ASSERT_TRUE(policy.Decide(machine.Sample()).may_work);
  machine.Advance(milliseconds(500));
  machine.user = Active();
  const IdleDecision decision = policy.Decide(machine.Sample());
  EXPECT_FALSE(decision.may_work);
  EXPECT_EQ(decision.reason, "user active");
}

TEST(IdlePolicyTest, ResumesOnlyAfterUserIdleMinutesAndTheHold) {
  IdlePolicy policy = MakePolicy(Config());
  ASSERT_EQ(policy.resume_hold(), seconds(10));  // 2 x poll_seconds
  FakeMachine machine;
  machine.user = Active();
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);

  machine.user = IdleFor(seconds(0));  // the user leaves
  int samples = 0;
  while (!policy.Decide(machine.Sample()).may_work) {
    machine.Advance(seconds(1));
    ASSERT_LT(++samples, 3600);
  }
  // Ten minutes of user inactivity, then ten seconds of hold.
  EXPECT_EQ(machine.user.idle_for, minutes(10) + seconds(10));
}

TEST(IdlePolicyTest, ShortIdleIsNamedInTheReason) {
  IdlePolicy policy = MakePolicy(Config());
  FakeMachine machine;
  machine.user = IdleFor(seconds(45));
  EXPECT_EQ(policy.Decide(machine.Sample()).reason, "user idle for 45 s of 10 min");
  machine.user = IdleFor(minutes(3));
  EXPECT_EQ(policy.Decide(machine.Sample()).reason, "user idle for 3 min of 10 min");
}

TEST(IdlePolicyTest, CpuLoadHysteresisKeepsALoadAtTheLimitFromFlapping) {
  IdlePolicy policy = MakePolicy(Config());
  FakeMachine machine;
  // A load wobbling around the limit (50%): one excursion stops work...
  const std::vector<double> loads = {0.30, 0.52, 0.48, 0.45, 0.49, 0.47, 0.50, 0.44, 0.46, 0.49};
  std::vector<bool> answers;
  for (double load : loads) {
    machine.other_cpu = load;
    answers.push_back(policy.Decide(machine.Sample()).may_work);
    machine.Advance(seconds(5));
  }
  // ...and work resumes only once the load stays at or below 40% for the hold.
  EXPECT_EQ(answers, (std::vector<bool>{true, false, false, false, false, false, false, false,
                                        false, false}));
  machine.other_cpu = 0.40;
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);  // the hold starts
  machine.Advance(seconds(5));
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);
  machine.Advance(seconds(5));
  EXPECT_TRUE(policy.Decide(machine.Sample()).may_work);
  // Working again, the full limit applies.
  machine.other_cpu = 0.50;
  EXPECT_TRUE(policy.Decide(machine.Sample()).may_work);
  machine.other_cpu = 0.51;
  const IdleDecision decision = policy.Decide(machine.Sample());
  EXPECT_FALSE(decision.may_work);
  EXPECT_EQ(decision.reason, "other processes use 51% of the CPUs (limit 50%)");
}

TEST(IdlePolicyTest, AnObstacleDuringTheHoldRestartsIt) {
  HysteresisSettings hysteresis;
  hysteresis.resume_hold = seconds(10);
  IdlePolicy policy = MakePolicy(Config(), hysteresis);
  FakeMachine machine;
  machine.other_cpu = 0.9;
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);
  machine.other_cpu = 0.1;
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);
  machine.Advance(seconds(8));
  machine.other_cpu = 0.6;  // a burst
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);
  machine.other_cpu = 0.1;
  machine.Advance(seconds(1));
  const IdleDecision holding = policy.Decide(machine.Sample());
  EXPECT_FALSE(holding.may_work);
  EXPECT_EQ(holding.reason, "idle again for 0 s of the 10 s before resuming");
  machine.Advance(seconds(9));
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);
  machine.Advance(seconds(1));
  EXPECT_TRUE(policy.Decide(machine.Sample()).may_work);
}

TEST(IdlePolicyTest, MaxOtherCpuOfOneIgnoresTheLoad) {
  IdleConfig config = Config();
  config.max_other_cpu = 1.0;
  IdlePolicy policy = MakePolicy(config);
  FakeMachine machine;
  machine.other_cpu = 1.0;
  EXPECT_TRUE(policy.Decide(machine.Sample()).may_work);
}

TEST(IdlePolicyTest, ScheduleAllowsOnlyItsHours) {
  IdleConfig config = Config();
  config.schedule = "Mon-Fri 18:00-08:00, Sat-Sun 00:00-24:00";
  IdlePolicy policy = MakePolicy(config, HysteresisSettings{milliseconds(0), 0.8});
  FakeMachine machine;
  machine.local = {2, 12 * 60};  // Wednesday noon: office hours
  const IdleDecision office = policy.Decide(machine.Sample());
  EXPECT_FALSE(office.may_work);
  EXPECT_EQ(office.reason,
            "outside the schedule 'Mon-Fri 18:00-08:00, Sat-Sun 00:00-24:00' (Wed 12:00)");
  machine.local = {2, 18 * 60};
  const IdleDecision evening = policy.Decide(machine.Sample());
  EXPECT_TRUE(evening.may_work);
  EXPECT_EQ(evening.reason, "idle: user idle 60 min, other CPU 0%, within the schedule");
  machine.local = {3, 8 * 60};  // Thursday 08:00: the office opens
  EXPECT_FALSE(policy.Decide(machine.Sample()).may_work);
}

TEST(IdlePolicyTest, DisabledPolicyAlwaysWorks) {
  IdleConfig config = Config();
  config.enabled = false;
  IdlePolicy policy = MakePolicy(config);
  FakeMachine machine;
  machine.user = Active();
  machine.other_cpu = 1.0;
  const IdleDecision decision = policy.Decide(machine.Sample());
  EXPECT_TRUE(decision.may_work);
  EXPECT_EQ(decision.reason, "idle policy disabled");
}

TEST(IdlePolicyTest, UnknownSourcesCountAsIdleAndAreLoggedOnce) {
  std::vector<std::string> logged;
  loop::SetLogSink([&](std::string_view line) { logged.emplace_back(line); });
  IdlePolicy policy = MakePolicy(Config());
  FakeMachine machine;
  machine.user = Unknown();
  machine.other_cpu = std::nullopt;
  for (int i = 0; i < 5; ++i) {
    const IdleDecision decision = policy.Decide(machine.Sample());
    EXPECT_TRUE(decision.may_work);
    EXPECT_EQ(decision.reason, "idle: user activity unknown");
    machine.Advance(seconds(1));
  }
  loop::SetLogSink(nullptr);
  ASSERT_EQ(logged.size(), 2u);
  EXPECT_NE(logged[0].find("user activity unknown (no system bus): treating the user as idle"),
            std::string::npos)
      << logged[0];
  EXPECT_NE(logged[1].find("CPU load unknown"), std::string::npos) << logged[1];
}

TEST(IdlePolicyTest, CreateRejectsAnInvalidConfigNamingTheKey) {
  IdleConfig config = Config();
  config.max_other_cpu = 2;
  Result<IdlePolicy> policy = IdlePolicy::Create(config);
  ASSERT_FALSE(policy.ok());
  EXPECT_EQ(policy.error().rfind("'idle.max_other_cpu' must be in (0, 1]", 0), 0u)
      << policy.error();
}

}  // namespace
}  // namespace radfarm::idle
