// The office emulation (bench/office/) at CI size: one capped machine against a capped farm of two
// agents on a coarse Cornell box with a small ray budget. The outputs must be render's byte for
// byte; no time is asserted.
#include "testing/office_emulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <thread>

#include "testing/temp_dir.h"

namespace radfarm::testing {
namespace {

TEST(OfficeEmulationTest, TwoCappedAgentsWriteRendersOutputs) {
  std::string why;
  const std::optional<testing::CpuController> cpu = testing::FindCpuController(&why);
  if (!cpu) GTEST_SKIP() << "skipped: " << why;
  // The master, two agents and the client, capped so that together they fit in this box's cores.
  const double cores = std::max(1u, std::thread::hardware_concurrency());
  OfficeSetup setup{*cpu,
                    {RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH},
                    std::max(testing::CpuGroup::kMinShare, std::min(0.4, 0.9 * cores / 4)),
                    std::chrono::seconds(240),
                    RADFARM_SOURCE_DIR "/scenes/cornell-box.toml",
                    {"--patch-size", "100", "--rays", "300000"},
                    // A job this small is otherwise solved by the master alone.
                    {"--local-round-rays", "0"}};
  const testing::TempDir dir("office-emulation");
  const MachineRun one = RunOneMachine(setup, dir.File("render"));
  EXPECT_GT(one.cpu_seconds, 0);
  std::filesystem::create_directories(dir.File("farm"));
  const FarmRun farm = RunFarm(setup, 2, dir.File("farm"), dir.File("out"));
  EXPECT_EQ(farm.agents, 2u);
  EXPECT_GT(farm.agents_cpu, 0);
  EXPECT_GT(farm.client_cpu, 0);
  for (const std::string& name : DifferingOutputs(dir.File("render"), dir.File("out"))) {
    ADD_FAILURE() << name << " differs from render's";
  }
}

TEST(OfficeEmulationTest, AmdahlsFitRecoversItsOwnModel) {
  // T(N) = 4 + 12 / N exactly at N = 1, 2, 4.
  const AmdahlFit fit = FitAmdahl({{1, 16}, {2, 10}, {4, 7}});
  EXPECT_NEAR(fit.serial, 4, 1e-9);
  EXPECT_NEAR(fit.parallel, 12, 1e-9);
  EXPECT_NEAR(fit.Predict(100), 4.12, 1e-9);
}

}  // namespace
}  // namespace radfarm::testing
