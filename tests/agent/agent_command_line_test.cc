// radfarm-agent's command line, run as a process: help, usage and input errors, exit codes.
#include <gtest/gtest.h>

#include "testing/child_process.h"
#include "testing/temp_dir.h"
#include "tests/agent/agent_process.h"
#include "tests/agent/test_farm.h"

namespace radfarm::agent::testing {
namespace {

using radfarm::testing::CommandResult;
using radfarm::testing::RunCommand;

CommandResult RunAgent(std::vector<std::string> args) {
  args.insert(args.begin(), RADFARM_AGENT_PATH);
  return RunCommand(args);
}

TEST(AgentCommandLineTest, HelpListsEveryFlagAndExitsZero) {
  const CommandResult help = RunAgent({"--help"});
  EXPECT_EQ(help.exit_code, 0);
  for (const char* flag :
       {"--master", "--secret-file", "--state-dir", "--threads", "--name", "--config",
        "--log-level", "--slowdown", "--exit-when-idle", "--idle-source"}) {
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
  }
}

TEST(AgentCommandLineTest, UsageErrorsExitTwo) {
  ScratchDir dir;
  WriteSecretFile(dir.File("key"), TestSecret(1));
  const std::string key = dir.File("key");
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"--secret-file", key}, "no master"},
      {{"--master", "127.0.0.1:7000"}, "no secret file"},
      {{"--master", "nowhere", "--secret-file", key}, "--master: expected HOST:PORT"},
      {{"--master", "h:1", "--secret-file", key, "--threads", "0"}, "--threads"},
      {{"--master", "h:1", "--secret-file", key, "--slowdown", "0.5"}, "--slowdown"},
      {{"--master", "h:1", "--secret-file", key, "--name", "bad name"}, "--name: must be"},
      {{"--master", "h:1", "--secret-file", key, "--exit-when-idle", "-1"}, "--exit-when-idle"},
      {{"--master", "h:1", "--secret-file", key, "--log-level", "loud"}, "--log-level"},
      {{"--master", "h:1", "--secret-file", key, "--bogus"}, "--bogus"},
      {{"--master", "h:1", "--secret-file", key, "--idle-source", dir.File("user")},
       "--idle-source (idle_source) needs the idle policy"},
  };
  for (const Case& c : cases) {
    const CommandResult result = RunAgent(c.args);
    EXPECT_EQ(result.exit_code, 2) << c.message;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
  }
}

TEST(AgentCommandLineTest, AMissingOrBadSecretFileIsNamed) {
  ScratchDir dir;
  const CommandResult missing =
      RunAgent({"--master", "127.0.0.1:7000", "--secret-file", dir.File("nope")});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find(dir.File("nope") + ": cannot read the farm secret"), std::string::npos)
      << missing.err;

  WriteTextFile(dir.File("short"), "abcd\n");
  const CommandResult short_key =
      RunAgent({"--master", "127.0.0.1:7000", "--secret-file", dir.File("short")});
  EXPECT_EQ(short_key.exit_code, 2);
  EXPECT_NE(short_key.err.find(dir.File("short") + ": not a farm secret"), std::string::npos)
      << short_key.err;
  EXPECT_EQ(short_key.err.find("abcd"), std::string::npos) << "the key file is never quoted";
}

TEST(AgentCommandLineTest, ConfigFileErrorsNameTheFileAndLine) {
  ScratchDir dir;
  WriteTextFile(dir.File("agent.toml"), "master = \"127.0.0.1:7000\"\nthreds = 2\n");
  const CommandResult result = RunAgent({"--config", dir.File("agent.toml")});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find(dir.File("agent.toml") + ":2: 'threds' is not a setting"),
            std::string::npos)
      << result.err;
}

TEST(AgentCommandLineTest, AnUnusableStateDirectoryExitsTwo) {
  ScratchDir dir;
  WriteSecretFile(dir.File("key"), TestSecret(1));
  WriteTextFile(dir.File("file"), "x");
  const CommandResult result = RunAgent({"--master", "127.0.0.1:7000", "--secret-file",
                                         dir.File("key"), "--state-dir", dir.File("file")});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find(dir.File("file")), std::string::npos) << result.err;
}

TEST(AgentCommandLineTest, TheConfigFileSuppliesWhatTheFlagsDoNot) {
  // The config names the master and the secret; the flag overrides its name. The agent connects,
  // then --exit-when-idle (also from the file) lets it go.
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x7c);
  WriteSecretFile(dir.File("farm.key"), secret);
  FakeMaster master(secret);
  WriteTextFile(dir.File("agent.toml"), "master = \"" + master.address() +
                                            "\"\nsecret_file = \"farm.key\"\n"
                                            "name = \"from-file\"\nthreads = 1\n"
                                            "exit_when_idle_seconds = 0.1\n");
  const CommandResult result =
      RunAgent({"--config", dir.File("agent.toml"), "--name", "from-flag"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("connected to " + master.address() + " as from-flag (agent id 1)"),
            std::string::npos)
      << result.err;
  EXPECT_EQ(master.Snapshot().agent_names, std::vector<std::string>{"from-flag"});
}

}  // namespace
}  // namespace radfarm::agent::testing
