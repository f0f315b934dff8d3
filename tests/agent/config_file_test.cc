#include "agent/config_file.h"

#include <gtest/gtest.h>

#include "agent/agent_settings.h"
#include "tests/agent/agent_process.h"

namespace radfarm::agent {
namespace {

using testing::ScratchDir;
using testing::WriteTextFile;

// Loads `text` as DIR/agent.toml; the error, or "" on success.
std::string ErrorOf(const ScratchDir& dir, const std::string& text) {
  const std::string path = dir.File("agent.toml");
  WriteTextFile(path, text);
  Result<AgentOptions> options = LoadConfigFile(path);
  return options ? "" : options.error();
}

TEST(ConfigFileTest, ReadsEveryKey) {
  ScratchDir dir;
  const std::string path = dir.File("agent.toml");
  WriteTextFile(path,
                "master = \"farm.example.org:7070\"\n"
                "secret_file = \"farm.key\"\n"
                "state_dir = \"/var/lib/radfarm-agent\"\n"
                "threads = 3\n"
                "name = \"office-12\"\n"
                "log_level = \"warning\"\n"
                "slowdown = 2.5\n"
                "exit_when_idle_seconds = 600\n");
  Result<AgentOptions> options = LoadConfigFile(path);
  ASSERT_TRUE(options.ok()) << options.error();
  EXPECT_EQ(options->master->host, "farm.example.org");
  EXPECT_EQ(options->master->port, 7070);
  EXPECT_EQ(*options->secret_file, dir.File("farm.key"));  // relative to the config file
  EXPECT_EQ(*options->state_dir, "/var/lib/radfarm-agent");
  EXPECT_EQ(*options->threads, 3u);
  EXPECT_EQ(*options->name, "office-12");
  EXPECT_EQ(*options->log_level, loop::LogLevel::kWarning);
  EXPECT_EQ(*options->slowdown, 2.5);
  EXPECT_EQ(*options->exit_when_idle_seconds, 600.0);
}

TEST(ConfigFileTest, AnEmptyFileSetsNothing) {
  ScratchDir dir;
  EXPECT_EQ(ErrorOf(dir, "# nothing\n"), "");
}

TEST(ConfigFileTest, ErrorsNameTheFileLineAndKey) {
  ScratchDir dir;
  const std::string at = dir.File("agent.toml") + ":";
  EXPECT_EQ(ErrorOf(dir, "threads = 2\n\ntreads = 4\n"),
            at + "3: 'treads' is not a setting (unknown key)");
  EXPECT_EQ(ErrorOf(dir, "threads = \"four\"\n"),
            at + "1: 'threads' must be an integer, not a string");
  EXPECT_EQ(ErrorOf(dir, "name = \"a\"\nthreads = 0\n"),
            at + "2: 'threads' must be in [1, 1024], got 0");
  EXPECT_EQ(ErrorOf(dir, "threads = 5000\n"), at + "1: 'threads' must be in [1, 1024], got 5000");
  EXPECT_EQ(ErrorOf(dir, "slowdown = 0.5\n"), at + "1: 'slowdown' must be >= 1, got 0.5");
  EXPECT_EQ(ErrorOf(dir, "slowdown = true\n"),
            at + "1: 'slowdown' must be a number, not a boolean");
  EXPECT_EQ(ErrorOf(dir, "exit_when_idle_seconds = 0\n"),
            at + "1: 'exit_when_idle_seconds' must be > 0, got 0");
  EXPECT_EQ(ErrorOf(dir, "log_level = \"loud\"\n"),
            at + "1: 'log_level' must be debug, info, warning or error, got 'loud'");
  EXPECT_EQ(ErrorOf(dir, "name = \"no spaces\"\n"),
            at + "1: 'name' must be 1 to 64 characters of A-Z a-z 0-9 . _ : @ -, got 'no spaces'");
  EXPECT_EQ(ErrorOf(dir, "\n[master]\nhost = \"x\"\n"),
            at + "2: 'master' must be a string, not a table");
  EXPECT_EQ(ErrorOf(dir, "secret_file = \"\"\n"), at + "1: 'secret_file' must not be empty");
}

TEST(ConfigFileTest, MasterMustBeHostAndPort) {
  ScratchDir dir;
  const std::string at = dir.File("agent.toml") + ":";
  EXPECT_EQ(ErrorOf(dir, "master = \"farm\"\n"),
            at + "1: 'master': expected HOST:PORT, got 'farm' (missing ':PORT')");
  EXPECT_EQ(ErrorOf(dir, "master = \"farm:0\"\n"),
            at + "1: 'master': expected HOST:PORT, got 'farm:0' (port 0 is not a master's port)");
}

TEST(ConfigFileTest, SyntaxErrorsNameTheLine) {
  ScratchDir dir;
  const std::string error = ErrorOf(dir, "threads = 2\nname = \n");
  EXPECT_EQ(error.rfind(dir.File("agent.toml") + ":2: ", 0), 0u) << error;
}

TEST(ConfigFileTest, AMissingFileIsNamed) {
  Result<AgentOptions> options = LoadConfigFile("/nonexistent/agent.toml");
  ASSERT_FALSE(options.ok());
  EXPECT_EQ(options.error().rfind("/nonexistent/agent.toml: cannot read the config file", 0), 0u)
      << options.error();
}

TEST(ConfigFileTest, TheIdleTableIsTheIdlePolicy) {
  ScratchDir dir;
  const std::string path = dir.File("agent.toml");
  WriteTextFile(path,
                "threads = 2\n"
                "idle_source = \"user-state\"\n"
                "[idle]\n"
                "user_idle_minutes = 3\n"
                "max_other_cpu = 0.25\n"
                "schedule = \"Mon-Fri 18:00-08:00\"\n"
                "poll_seconds = 2\n");
  Result<AgentOptions> options = LoadConfigFile(path);
  ASSERT_TRUE(options.ok()) << options.error();
  ASSERT_TRUE(options->idle.has_value());
  EXPECT_TRUE(options->idle->enabled);
  EXPECT_EQ(options->idle->user_idle_minutes, 3);
  EXPECT_EQ(options->idle->max_other_cpu, 0.25);
  EXPECT_EQ(options->idle->schedule, "Mon-Fri 18:00-08:00");
  EXPECT_EQ(options->idle->poll_seconds, 2);
  EXPECT_EQ(*options->idle_source, dir.File("user-state"));  // relative to the config file

  // An empty table is the policy with its defaults; no table, no policy.
  WriteTextFile(path, "[idle]\n");
  options = LoadConfigFile(path);
  ASSERT_TRUE(options.ok()) << options.error();
  ASSERT_TRUE(options->idle.has_value());
  EXPECT_EQ(options->idle->user_idle_minutes, idle::IdleConfig{}.user_idle_minutes);
  WriteTextFile(path, "threads = 2\n");
  options = LoadConfigFile(path);
  ASSERT_TRUE(options.ok()) << options.error();
  EXPECT_FALSE(options->idle.has_value());
}

TEST(ConfigFileTest, IdleErrorsNameTheFileLineAndDottedKey) {
  ScratchDir dir;
  const std::string at = dir.File("agent.toml") + ":";
  const std::string cpu =
      ErrorOf(dir, "threads = 2\n[idle]\nenabled = true\nmax_other_cpu = 1.5\n");
  EXPECT_EQ(cpu.rfind(at + "4: 'idle.max_other_cpu' must be in (0, 1]", 0), 0u) << cpu;
  const std::string unknown = ErrorOf(dir, "[idle]\nidle_minutes = 5\n");
  EXPECT_EQ(unknown.rfind(at + "2: 'idle.idle_minutes' is not a key", 0), 0u) << unknown;
  const std::string schedule = ErrorOf(dir, "[idle]\n\nschedule = \"weekends\"\n");
  EXPECT_EQ(schedule.rfind(at + "3: 'idle.schedule' is not a schedule", 0), 0u) << schedule;
  EXPECT_EQ(ErrorOf(dir, "threads = 1\nidle = 5\n"),
            at + "2: 'idle' must be a table ([idle]), not an integer");
  EXPECT_EQ(ErrorOf(dir, "idle_source = \"\"\n"), at + "1: 'idle_source' must not be empty");
}

TEST(AgentSettingsTest, AnIdleSourceNeedsAnEnabledIdlePolicy) {
  AgentOptions flags;
  flags.master = loop::HostPort{"h", 1};
  flags.secret_file = "/k";
  flags.idle_source = "/run/user-state";
  AgentOptions file;
  Result<AgentSettings> without = ResolveSettings(flags, file);
  ASSERT_FALSE(without.ok());
  EXPECT_NE(without.error().find("--idle-source (idle_source) needs the idle policy"),
            std::string::npos)
      << without.error();
  file.idle = idle::IdleConfig{};
  file.idle->enabled = false;
  EXPECT_FALSE(ResolveSettings(flags, file).ok());
  file.idle->enabled = true;
  Result<AgentSettings> with = ResolveSettings(flags, file);
  ASSERT_TRUE(with.ok()) << with.error();
  EXPECT_TRUE(with->idle_policy_enabled());
  EXPECT_EQ(with->idle_source, "/run/user-state");
}

TEST(AgentSettingsTest, CommandLineWinsOverTheFileAndDefaultsFillTheRest) {
  AgentOptions file;
  file.master = loop::HostPort{"file-host", 1};
  file.secret_file = "/file.key";
  file.threads = 3;
  file.slowdown = 4;
  AgentOptions flags;
  flags.master = loop::HostPort{"flag-host", 2};
  flags.name = "flagged";
  Result<AgentSettings> settings = ResolveSettings(flags, file);
  ASSERT_TRUE(settings.ok()) << settings.error();
  EXPECT_EQ(settings->master.host, "flag-host");
  EXPECT_EQ(settings->secret_file, "/file.key");
  EXPECT_EQ(settings->threads, 3u);
  EXPECT_EQ(settings->name, "flagged");
  EXPECT_EQ(settings->slowdown, 4);
  EXPECT_EQ(settings->state_dir, "");
  EXPECT_EQ(settings->exit_when_idle_seconds, 0);
  EXPECT_EQ(settings->log_level, loop::LogLevel::kInfo);
  EXPECT_FALSE(settings->idle_policy_enabled());  // no [idle] table: work always
}

TEST(AgentSettingsTest, MasterAndSecretFileAreRequired) {
  AgentOptions none;
  Result<AgentSettings> no_master = ResolveSettings(none, none);
  ASSERT_FALSE(no_master.ok());
  EXPECT_NE(no_master.error().find("no master"), std::string::npos);
  AgentOptions master_only;
  master_only.master = loop::HostPort{"h", 1};
  Result<AgentSettings> no_secret = ResolveSettings(master_only, none);
  ASSERT_FALSE(no_secret.ok());
  EXPECT_NE(no_secret.error().find("no secret file"), std::string::npos);
}

TEST(AgentSettingsTest, DefaultsAreAllCoresAndTheSanitisedHostName) {
  AgentOptions flags;
  flags.master = loop::HostPort{"h", 1};
  flags.secret_file = "/k";
  Result<AgentSettings> settings = ResolveSettings(flags, {});
  ASSERT_TRUE(settings.ok()) << settings.error();
  EXPECT_EQ(settings->threads, DefaultThreads());
  EXPECT_GE(settings->threads, 1u);
  EXPECT_EQ(settings->name, DefaultAgentName());
  EXPECT_EQ(settings->name, SanitiseAgentName(settings->name));
}

TEST(AgentSettingsTest, SanitiseAgentNameKeepsTheProtocolsCharacters) {
  EXPECT_EQ(SanitiseAgentName("office-12.example.org"), "office-12.example.org");
  EXPECT_EQ(SanitiseAgentName("my host/é"), "my-host---");
  EXPECT_EQ(SanitiseAgentName(""), "agent");
  EXPECT_EQ(SanitiseAgentName(std::string(100, 'a')), std::string(64, 'a'));
}

}  // namespace
}  // namespace radfarm::agent
