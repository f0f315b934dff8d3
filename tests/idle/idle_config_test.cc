#include "idle/idle_config.h"

#include <gtest/gtest.h>

namespace radfarm::idle {
namespace {

// Parses `text` as agent.conf and reads its [idle] table.
Result<IdleConfig> ParseAgentConf(std::string_view text) {
  // toml++ throws on bad TOML (exceptions are on); every text here is valid TOML.
  const toml::table parsed = toml::parse(text, std::string_view("agent.conf"));
  const toml::table* idle = parsed["idle"].as_table();
  EXPECT_NE(idle, nullptr);
  return ParseIdleConfig(*idle, "agent.conf");
}

std::string ErrorOf(std::string_view text) {
  Result<IdleConfig> config = ParseAgentConf(text);
  EXPECT_FALSE(config.ok()) << text;
  return config.ok() ? std::string() : config.error();
}

TEST(IdleConfigTest, EveryKey) {
  Result<IdleConfig> config = ParseAgentConf(R"(master = "m:7878"
[idle]
enabled = false
user_idle_minutes = 0
max_other_cpu = 1
schedule = "Mon-Fri 18:00-08:00"
poll_seconds = 60
)");
  ASSERT_TRUE(config.ok()) << config.error();
  EXPECT_FALSE(config->enabled);
  EXPECT_EQ(config->user_idle_minutes, 0);
  EXPECT_EQ(config->max_other_cpu, 1.0);
  EXPECT_EQ(config->schedule, "Mon-Fri 18:00-08:00");
  EXPECT_EQ(config->poll_seconds, 60);
}

TEST(IdleConfigTest, AbsentKeysKeepTheirDefaults) {
  Result<IdleConfig> config = ParseAgentConf("[idle]\nmax_other_cpu = 0.25\n");
  ASSERT_TRUE(config.ok()) << config.error();
  const IdleConfig defaults;
  EXPECT_EQ(config->enabled, defaults.enabled);
  EXPECT_EQ(config->user_idle_minutes, defaults.user_idle_minutes);
  EXPECT_EQ(config->max_other_cpu, 0.25);
  EXPECT_EQ(config->schedule, "");
  EXPECT_EQ(config->poll_seconds, defaults.poll_seconds);
  EXPECT_TRUE(Validate(defaults).ok());
}

TEST(IdleConfigTest, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(ErrorOf("[idle]\n\nmax_other_cpu = 1.5\n"),
            "agent.conf:3: 'idle.max_other_cpu' must be in (0, 1] (a fraction of all cores), "
            "got 1.5");
  EXPECT_EQ(ErrorOf("[idle]\nmax_other_cpu = 0\n"),
            "agent.conf:2: 'idle.max_other_cpu' must be in (0, 1] (a fraction of all cores), "
            "got 0");
  EXPECT_EQ(ErrorOf("[idle]\nenabled = \"yes\"\n"),
            "agent.conf:2: 'idle.enabled' must be true or false, not a string");
  EXPECT_EQ(ErrorOf("[idle]\nuser_idle_minutes = -1\n"),
            "agent.conf:2: 'idle.user_idle_minutes' must be in [0, 10080], got -1");
  EXPECT_EQ(ErrorOf("[idle]\nuser_idle_minutes = 2.5\n"),
            "agent.conf:2: 'idle.user_idle_minutes' must be an integer, not a real number");
  EXPECT_EQ(ErrorOf("[idle]\npoll_seconds = 0\n"),
            "agent.conf:2: 'idle.poll_seconds' must be in [1, 3600], got 0");
  EXPECT_EQ(ErrorOf("[idle]\nmax_other_cpu = \"half\"\n"),
            "agent.conf:2: 'idle.max_other_cpu' must be a number, not a string");
  EXPECT_EQ(ErrorOf("[idle]\nschedule = \"Mon-Fri 18:00\"\n"),
            "agent.conf:2: 'idle.schedule' is not a schedule: entry 1 'Mon-Fri 18:00': expected "
            "[DAYS ]HH:MM-HH:MM, e.g. 'Mon-Fri 18:00-08:00'");
  EXPECT_EQ(ErrorOf("[idle]\nschedule = 18\n"),
            "agent.conf:2: 'idle.schedule' must be a string, not an integer");
  EXPECT_EQ(ErrorOf("[idle]\nenabled = true\nidle_minutes = 5\n"),
            "agent.conf:3: 'idle.idle_minutes' is not a key of this table (enabled, "
            "user_idle_minutes, max_other_cpu, schedule, poll_seconds)");
}

TEST(IdleConfigTest, ValidateNamesTheKeyOfAConfigBuiltInCode) {
  IdleConfig config;
  config.poll_seconds = 0;
  Status status = Validate(config);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error(), "'idle.poll_seconds' must be in [1, 3600], got 0");

  config = IdleConfig();
  config.schedule = "Sun-Xyz 01:00-02:00";
  status = Validate(config, "--idle-");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error(),
            "'--idle-schedule' is not a schedule: entry 1 'Sun-Xyz 01:00-02:00': unknown day 'Xyz' "
            "(Mon..Sun)");
}

}  // namespace
}  // namespace radfarm::idle
