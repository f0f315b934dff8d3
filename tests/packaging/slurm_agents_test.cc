// Agents as Slurm batch jobs, for real: a one-node Slurm cluster from Debian's
// slurm-wlm and munge on this machine (slurm_cluster.h), a radfarmd on loopback, and
// `sbatch --array` of the shipped packaging/scheduler/radfarm-agent.slurm.sh with the config its
// comments document. The agents connect, do every round of the job (the master computes none
// itself), the job ends byte-identical to `radfarm render`, the agents exit by themselves through
// --exit-when-idle, Slurm records each array task as completed with exit code 0, and nothing is
// left running.
//
// It needs root (slurmd starts job steps as the submitting user) and the Debian packages
// slurm-wlm and munge (scripts/install-deps --tests): without them it fails, since CI has both.
#include <gtest/gtest.h>
#include <unistd.h>

#include <sstream>

#include "batch_example.h"
#include "slurm_cluster.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

using packaging::testing::DifferingOutputs;
using packaging::testing::ExampleAgentConfig;
using packaging::testing::SlurmCluster;
using packaging::testing::WritePrivateFile;

const std::string kScript = RADFARM_SOURCE_DIR "/packaging/scheduler/radfarm-agent.slurm.sh";
constexpr auto kAgentsExitTimeout = std::chrono::seconds(120);

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

using SlurmAgentsTest = FarmTest;

TEST_F(SlurmAgentsTest, AnArrayOfAgentsFinishesAJobLikeRenderAndExits) {
  if (geteuid() != 0) {
    GTEST_SKIP() << "slurmd must run as root to start job steps as the submitting user; run the "
                    "tests as root (CI does)";
  }
  ASSERT_EQ(SlurmCluster::MissingPrograms(), "")
      << "install the Debian packages slurm-wlm and munge (scripts/install-deps --tests)";
  TempDir slurm_dir("radfarm-slurm");
  SlurmCluster slurm(slurm_dir.path());
  const std::string started = slurm.Start();
  ASSERT_EQ(started, "") << slurm.Logs();

  // Every round on the agents: the job cannot end unless they work.
  StartMaster({"--local-round-rays", "0"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_GE(id, 1);

  const std::string conf = slurm_dir.File("agent-batch.conf");
  const std::string config =
      ExampleAgentConfig(ReadFile(kScript), master_address(), farm_.secret_file());
  ASSERT_NE(config, "") << kScript << " documents no agent config";
  ASSERT_TRUE(WritePrivateFile(conf, config));
  // The script's #SBATCH sizes are for real nodes; like a user, the test asks for what this one
  // has. Its environment reaches the job (sbatch exports it by default).
  const CommandResult submitted =
      slurm.Client({"sbatch", "--parsable", "--array=1-2", "--cpus-per-task=1", "--mem=256M",
                    "--chdir=" + slurm_dir.path(),
                    "--output=" + slurm_dir.File("radfarm-agent-%A_%a.log"), kScript},
                   {"RADFARM_AGENT_CONF=" + conf, "RADFARM_AGENT=" RADFARM_AGENT_PATH,
                    "RADFARM_EXIT_WHEN_IDLE=3"});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err << slurm.Logs();
  const std::string array = submitted.out.substr(0, submitted.out.find_first_of(";\n"));
  ASSERT_FALSE(array.empty());
  const auto agent_log = [&](int task) {
    return ReadFile(slurm_dir.File("radfarm-agent-" + array + "_" + std::to_string(task) + ".log"));
  };

  ASSERT_TRUE(WaitForState(id, "done")) << agent_log(1) << agent_log(2) << slurm.Logs();
  TempDir rendered;
  std::vector<std::string> render = {
      RADFARM_CLI_PATH, "render",        RADFARM_SOURCE_DIR "/scenes/cornell-box.toml",
      "--out",          rendered.path(), "-q"};
  render.insert(render.end(), kShortJob.begin(), kShortJob.end());
  ASSERT_EQ(RunCommand(render).exit_code, 0);
  const std::string fetched = Path("fetched");
  ASSERT_EQ(Cli({"fetch", std::to_string(id), "--out", fetched}).exit_code, 0);
  EXPECT_EQ(DifferingOutputs(fetched, rendered.path()), "") << "differ from radfarm render";
  const std::string master_log = MasterLog();
  for (int task : {1, 2}) {
    const std::string name = "slurm-" + array + "-" + std::to_string(task);
    EXPECT_GE(CountLines(master_log, name + "@"), 1u) << name << " never connected";
  }

  // The agents leave by themselves once there is no work, and Slurm saw them succeed.
  ASSERT_TRUE(WaitUntil(
      [&] {
        return slurm.Client({"squeue", "--noheader", "--jobs", array}).out.empty();
      },
      kAgentsExitTimeout, std::chrono::milliseconds(200)))
      << slurm.Client({"squeue"}).out << agent_log(1) << agent_log(2);
  const std::vector<std::string> tasks =
      Lines(slurm.Client({"scontrol", "--oneliner", "show", "job", array}).out);
  EXPECT_EQ(tasks.size(), 2u);
  for (const std::string& task : tasks) {
    EXPECT_NE(task.find("JobState=COMPLETED"), std::string::npos) << task;
    EXPECT_NE(task.find("ExitCode=0:0"), std::string::npos) << task;
  }
  for (int task : {1, 2}) {
    const std::string log = agent_log(task);
    EXPECT_NE(log.find("connected to " + master_address()), std::string::npos) << log;
    EXPECT_NE(log.find("no lease for 3 s"), std::string::npos) << log;
  }
  EXPECT_EQ(slurm.Leftovers(), std::vector<std::string>{}) << "still running after the jobs ended";
}

}  // namespace
}  // namespace radfarm::testing
