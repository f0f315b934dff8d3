// The HTCondor example (packaging/scheduler/radfarm-agent.htcondor.sub) run as HTCondor's starter
// runs a vanilla-universe job, without HTCondor's daemons: the submit file's macros expanded (with
// the overrides a user passes as `condor_submit -a`), a scratch directory per job holding
// transfer_input_files, the executable started there with the job's arguments and its output in
// the job's output file. Two such agents, with the config the file's comments document, finish a
// job byte-identical to `radfarm render` and exit 0 by themselves, as the Slurm ones do
// (slurm_agents_test.cc).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include "batch_example.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

namespace fs = std::filesystem;
using packaging::testing::DifferingOutputs;
using packaging::testing::ExampleAgentConfig;
using packaging::testing::WritePrivateFile;

const std::string kSubmitFile =
    RADFARM_SOURCE_DIR "/packaging/scheduler/radfarm-agent.htcondor.sub";

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string Strip(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// A submit description: its commands (keys in lower case, as HTCondor treats them) and the
// number of jobs its `queue` line asks for.
struct SubmitDescription {
  std::map<std::string, std::string> commands;
  int queue = 0;
};

SubmitDescription Parse(const std::string& text) {
  SubmitDescription description;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    line = Strip(line);
    if (line.empty() || line[0] == '#') continue;
    if (Lower(line).rfind("queue", 0) == 0) {
      const std::string count = Strip(line.substr(5));
      description.queue = count.empty() ? 1 : std::stoi(count);
      continue;
    }
    const size_t equals = line.find('=');
    if (equals == std::string::npos) continue;
    description.commands[Lower(Strip(line.substr(0, equals)))] = Strip(line.substr(equals + 1));
  }
  return description;
}

// $(name) expanded from the commands and `job` (Cluster, Process); an unknown macro is an error.
std::string Expand(const std::string& text, const std::map<std::string, std::string>& macros,
                   std::string* error) {
  std::string out;
  size_t at = 0;
  for (size_t open; (open = text.find("$(", at)) != std::string::npos;) {
    const size_t close = text.find(')', open);
    const std::string name = Lower(text.substr(open + 2, close - open - 2));
    out += text.substr(at, open - at);
    auto it = macros.find(name);
    if (close == std::string::npos || it == macros.end()) {
      *error = "unknown macro $(" + name + ") in: " + text;
      return "";
    }
    out += it->second;
    at = close + 1;
  }
  return out + text.substr(at);
}

// The "new syntax" arguments: double-quoted, split at white space (no quoting inside here).
std::vector<std::string> Arguments(const std::string& quoted) {
  std::vector<std::string> words;
  std::istringstream in(quoted.substr(1, quoted.size() - 2));
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

using HtcondorAgentsTest = FarmTest;

TEST_F(HtcondorAgentsTest, TwoJobsOfTheExampleFinishAJobLikeRenderAndExit) {
  SubmitDescription submit = Parse(ReadFile(kSubmitFile));
  ASSERT_GE(submit.queue, 1);
  std::map<std::string, std::string>& commands = submit.commands;
  // What the agent package and the Slurm example rely on.
  EXPECT_EQ(commands["universe"], "vanilla");
  EXPECT_EQ(commands["executable"], "/usr/bin/radfarm-agent");
  EXPECT_EQ(Lower(commands["transfer_executable"]), "false");
  EXPECT_EQ(commands["kill_sig"], "SIGTERM");
  EXPECT_EQ(commands["transfer_input_files"], "agent-batch.conf, secret");
  ASSERT_EQ(commands["arguments"].front(), '"');
  // `condor_submit -a 'exit_when_idle = 3' -a 'request_cpus = 1'`: a short idle time, and the
  // cores this test machine has.
  commands["exit_when_idle"] = "3";
  commands["request_cpus"] = "1";

  StartMaster({"--local-round-rays", "0"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_GE(id, 1);
  const std::string config = ExampleAgentConfig(ReadFile(kSubmitFile), master_address(), "secret");
  ASSERT_NE(config, "") << kSubmitFile << " documents no agent config";

  struct Job {
    std::string sandbox, name, output;
    std::unique_ptr<ChildProcess> process;
  };
  std::vector<Job> jobs;
  for (int process = 0; process < 2; ++process) {
    std::map<std::string, std::string> macros = commands;
    macros["cluster"] = "7";
    macros["process"] = std::to_string(process);
    std::string error;
    std::vector<std::string> args = {RADFARM_AGENT_PATH};  // installed as /usr/bin/radfarm-agent
    for (const std::string& word : Arguments(commands["arguments"])) {
      args.push_back(Expand(word, macros, &error));
      ASSERT_EQ(error, "");
    }
    Job job;
    job.sandbox = Path("execute-7." + std::to_string(process));
    fs::create_directory(job.sandbox);
    ASSERT_TRUE(WritePrivateFile(job.sandbox + "/agent-batch.conf", config));
    ASSERT_TRUE(WritePrivateFile(job.sandbox + "/secret", ReadFile(farm_.secret_file())));
    job.name = "condor-7-" + std::to_string(process);
    job.output = job.sandbox + "/" + Expand(commands["output"], macros, &error);
    ASSERT_EQ(error, "");
    // The starter runs the job in its sandbox: `cd` there, then the executable.
    args.insert(args.begin(), {"/bin/sh", "-c", "cd \"$0\" && exec \"$@\"", job.sandbox});
    job.process = std::make_unique<ChildProcess>(args, job.output);
    jobs.push_back(std::move(job));
  }

  ASSERT_TRUE(WaitForState(id, "done")) << jobs[0].process->Log() << jobs[1].process->Log();
  TempDir rendered;
  std::vector<std::string> render = {
      RADFARM_CLI_PATH, "render",        RADFARM_SOURCE_DIR "/scenes/cornell-box.toml",
      "--out",          rendered.path(), "-q"};
  render.insert(render.end(), kShortJob.begin(), kShortJob.end());
  ASSERT_EQ(RunCommand(render).exit_code, 0);
  const std::string fetched = Path("fetched");
  ASSERT_EQ(Cli({"fetch", std::to_string(id), "--out", fetched}).exit_code, 0);
  EXPECT_EQ(DifferingOutputs(fetched, rendered.path()), "") << "differ from radfarm render";

  for (Job& job : jobs) {
    EXPECT_GE(CountLines(MasterLog(), job.name + "@"), 1u) << job.name << " never connected";
    const std::optional<int> exit_code = job.process->WaitExit(std::chrono::seconds(120));
    ASSERT_TRUE(exit_code.has_value()) << job.name << " did not exit\n" << job.process->Log();
    EXPECT_EQ(*exit_code, 0) << job.process->Log();
    EXPECT_NE(job.process->Log().find("no lease for 3 s"), std::string::npos) << job.process->Log();
  }
}

}  // namespace
}  // namespace radfarm::testing
