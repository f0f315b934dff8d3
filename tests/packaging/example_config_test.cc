// packaging/etc/*.conf: every key is there, commented out but for the agent's idle policy, which is
// on as shipped; uncommented, each file is valid TOML and the agent's [idle] table passes the idle
// policy's own parser.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "idle/idle_config.h"
#include "shell.h"

#ifdef RADFARM_HAVE_MASTER_CONFIG
#include "daemon/config/master_config.h"
#endif
#ifdef RADFARM_HAVE_AGENT_CONFIG
#include "agent/config_file.h"
#endif

namespace radfarm::packaging {
namespace {

namespace fs = std::filesystem;

// The file with "#key = value" and "#[table]" lines uncommented (prose comments stay).
std::string Uncomment(const std::string& text) {
  static const std::regex setting("^#(\\[[a-z_]+\\]|[a-z_]+ = .*)$");
  std::istringstream lines(text);
  std::string out;
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    out += (std::regex_match(line, match, setting) ? match[1].str() : line) + "\n";
  }
  return out;
}

std::set<std::string> Keys(const toml::table& table) {
  std::set<std::string> keys;
  for (const auto& [key, node] : table) {
    if (!node.is_table()) keys.insert(std::string(key.str()));
  }
  return keys;
}

std::string ReadExample(const std::string& name) {
  return testing::ReadFile(fs::path(RADFARM_SOURCE_DIR) / "packaging/etc" / name);
}

// `text` written to `dir`/`name`; returns the path.
std::string WriteFile(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

toml::table ParseExample(const std::string& name) {
  const std::string text = ReadExample(name);
  EXPECT_FALSE(text.empty()) << name;
  try {
    return toml::parse(Uncomment(text), std::string_view(name));
  } catch (const toml::parse_error& error) {
    ADD_FAILURE() << name << " uncommented is not TOML: " << error;
    return {};
  }
}

TEST(ExampleConfigTest, MasterConfigNamesEveryKey) {
  // Shipped as is, nothing is set.
  EXPECT_TRUE(toml::parse(ReadExample("radfarmd.conf"), std::string_view("radfarmd.conf")).empty());
  const toml::table config = ParseExample("radfarmd.conf");
  const std::set<std::string> keys = Keys(config);
  for (const char* key : {"listen", "state_dir", "secret_file", "control", "heartbeat_ms",
                          "agent_timeout_ms", "log_level", "checkpoint_keep"}) {
    EXPECT_EQ(keys.count(key), 1u) << key;
  }
  EXPECT_EQ(config["listen"].value_or(std::string()), "0.0.0.0:7878");
  EXPECT_EQ(config["secret_file"].value_or(std::string()), "/etc/radfarm/secret");
  EXPECT_EQ(config["state_dir"].value_or(std::string()), "/var/lib/radfarm");
}

// An office desktop's agent computes only while its machine is idle: the shipped file sets the idle
// policy on and nothing else.
TEST(ExampleConfigTest, ShippedAgentConfigSetsOnlyTheIdlePolicyOn) {
  const toml::table shipped =
      toml::parse(ReadExample("agent.conf"), std::string_view("agent.conf"));
  EXPECT_EQ(shipped.size(), 1u);
  const toml::table* idle = shipped["idle"].as_table();
  ASSERT_NE(idle, nullptr);
  EXPECT_EQ(Keys(*idle), (std::set<std::string>{"enabled"}));
  EXPECT_EQ((*idle)["enabled"].value<bool>(), std::optional<bool>(true));
}

TEST(ExampleConfigTest, AgentConfigNamesEveryKeyAndItsIdleTableParses) {
  const toml::table config = ParseExample("agent.conf");
  EXPECT_EQ(Keys(config),
            (std::set<std::string>{"master", "secret_file", "state_dir", "threads", "name",
                                   "log_level", "slowdown", "exit_when_idle_seconds"}));
  const toml::table* idle = config["idle"].as_table();
  ASSERT_NE(idle, nullptr);
  EXPECT_EQ(Keys(*idle), (std::set<std::string>{"enabled", "user_idle_minutes", "max_other_cpu",
                                                "schedule", "poll_seconds"}));
  Result<idle::IdleConfig> parsed = idle::ParseIdleConfig(*idle, "agent.conf");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  // The example shows the defaults (but for the schedule, which is an example).
  const idle::IdleConfig defaults;
  EXPECT_EQ(parsed->enabled, defaults.enabled);
  EXPECT_EQ(parsed->user_idle_minutes, defaults.user_idle_minutes);
  EXPECT_EQ(parsed->max_other_cpu, defaults.max_other_cpu);
  EXPECT_EQ(parsed->poll_seconds, defaults.poll_seconds);
  EXPECT_FALSE(parsed->schedule.empty());
}

#ifdef RADFARM_HAVE_MASTER_CONFIG
// The example shows radfarmd's defaults: uncommented, it changes nothing.
TEST(ExampleConfigTest, RadfarmdReadsItsExampleAndItHoldsTheDefaults) {
  testing::TempDir dir;
  const std::string path =
      WriteFile(dir.path(), "radfarmd.conf", Uncomment(ReadExample("radfarmd.conf")));
  daemon::MasterConfig config;
  const Status read = daemon::ReadMasterConfigFile(path, &config);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_TRUE(daemon::CheckMasterConfig(config).ok());
  const daemon::MasterConfig defaults;
  EXPECT_EQ(config.listen, defaults.listen);
  EXPECT_EQ(config.state_dir, defaults.state_dir);
  EXPECT_EQ(config.secret_file, defaults.secret_file);
  EXPECT_EQ(config.control, defaults.control);
  EXPECT_EQ(config.heartbeat_ms, defaults.heartbeat_ms);
  EXPECT_EQ(config.agent_timeout_ms, defaults.agent_timeout_ms);
  EXPECT_EQ(config.handshake_timeout_ms, defaults.handshake_timeout_ms);
  EXPECT_EQ(config.control_timeout_ms, defaults.control_timeout_ms);
  EXPECT_EQ(config.hold_retry_ms, defaults.hold_retry_ms);
  EXPECT_EQ(config.max_store_bytes, defaults.max_store_bytes);
  EXPECT_EQ(config.log_level, defaults.log_level);
  EXPECT_EQ(config.checkpoint_keep, defaults.checkpoint_keep);
  EXPECT_EQ(config.checkpoint_seconds, defaults.checkpoint_seconds);
  EXPECT_EQ(config.checkpoint_time_share, defaults.checkpoint_time_share);
  EXPECT_EQ(config.max_running_jobs, defaults.max_running_jobs);
  EXPECT_EQ(config.lease_seconds, defaults.lease_seconds);
  EXPECT_EQ(config.max_agents, defaults.max_agents);
  EXPECT_EQ(config.max_unauthenticated, defaults.max_unauthenticated);
  EXPECT_EQ(config.max_connections_per_agent, defaults.max_connections_per_agent);
  EXPECT_EQ(config.max_frame_bytes_held, defaults.max_frame_bytes_held);
  EXPECT_EQ(config.allow_shared_secret, defaults.allow_shared_secret);
  EXPECT_EQ(config.local_round_rays, defaults.local_round_rays);
  EXPECT_EQ(config.keep_round_results, defaults.keep_round_results);
  EXPECT_EQ(config.keep_results_after_seconds, defaults.keep_results_after_seconds);
  EXPECT_EQ(config.verify_fraction, defaults.verify_fraction);
}
#endif

#ifdef RADFARM_HAVE_AGENT_CONFIG
// The agent's own reader finds the idle policy on in the file as shipped.
TEST(ExampleConfigTest, RadfarmAgentReadsTheShippedFileAsIdleOnly) {
  testing::TempDir dir;
  const std::string path = WriteFile(dir.path(), "agent.conf", ReadExample("agent.conf"));
  Result<agent::AgentOptions> options = agent::LoadConfigFile(path);
  ASSERT_TRUE(options.ok()) << options.error();
  ASSERT_TRUE(options->idle.has_value());
  EXPECT_TRUE(options->idle->enabled);
  // The rest of the policy keeps its defaults.
  const idle::IdleConfig defaults;
  EXPECT_EQ(options->idle->user_idle_minutes, defaults.user_idle_minutes);
  EXPECT_EQ(options->idle->max_other_cpu, defaults.max_other_cpu);
  EXPECT_EQ(options->idle->schedule, defaults.schedule);
  EXPECT_EQ(options->idle->poll_seconds, defaults.poll_seconds);
}

// The agent's reader takes every top-level key of the example. (The [idle] table is read by
// idle::ParseIdleConfig, tested above; it is cut here.)
TEST(ExampleConfigTest, RadfarmAgentReadsItsExample) {
  std::string text = Uncomment(ReadExample("agent.conf"));
  text = text.substr(0, text.find("\n[idle]"));
  testing::TempDir dir;
  const std::string path = WriteFile(dir.path(), "agent.conf", text);
  Result<agent::AgentOptions> options = agent::LoadConfigFile(path);
  ASSERT_TRUE(options.ok()) << options.error();
  ASSERT_TRUE(options->master.has_value());
  EXPECT_EQ(options->secret_file, "/etc/radfarm/secret");
  EXPECT_EQ(options->state_dir, "/var/lib/radfarm-agent");
  EXPECT_EQ(options->log_level, loop::LogLevel::kInfo);
  EXPECT_EQ(options->slowdown, 1.0);
  EXPECT_EQ(options->exit_when_idle_seconds, 300.0);
}
#endif

}  // namespace
}  // namespace radfarm::packaging
