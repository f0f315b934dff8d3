// A small fault campaign in CI (testing/fault_campaign.h; bench/faults runs the long one): a
// damaged store file refused at start, agents killed, frozen and restarted, the master killed
// three times, and (as root, on a tmpfs) the state directory filled to ENOSPC, while two short
// jobs run. Every job ends byte-identical to `radfarm render`, none lost or listed twice.
// RADFARM_FAULT_SEED=N re-runs a failing campaign's schedule.
#include "testing/fault_campaign.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

uint32_t CampaignSeed() {
  if (const char* seed = std::getenv("RADFARM_FAULT_SEED")) return uint32_t(std::stoul(seed));
  return std::random_device{}();
}

TEST_F(FarmTest, AFaultCampaignEndsEveryJobLikeRenderAndLosesNone) {
  FaultPlan plan;
  plan.seed = CampaignSeed();
  std::printf("fault campaign seed %u (RADFARM_FAULT_SEED=%u re-runs it)\n", plan.seed, plan.seed);
  plan.agents = 2;
  plan.jobs = 2;
  plan.agent_faults = 10;
  plan.master_kills = 3;
  plan.store_truncations = 1;
  plan.disk_fills = ::geteuid() == 0 ? 1 : 0;  // mounting the tmpfs needs root
  plan.job_file = RADFARM_SOURCE_DIR "/scenes/cornell-box.toml";
  plan.job_flags = kShortJob;
  plan.master_flags = {"--heartbeat-ms",         "200",  "--agent-timeout-ms", "2000",
                       "--handshake-timeout-ms", "2000", "--hold-retry-ms",    "200"};
  std::filesystem::create_directories(Path("campaign"));
  const CampaignOutcome out =
      RunFaultCampaign({RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, Path("campaign"),
                       plan, ReferencePatches("cornell-box.toml", kShortJob),
                       [](const std::string& line) { std::printf("%s\n", line.c_str()); });
  EXPECT_TRUE(out.ok()) << "seed " << plan.seed << "\n" << ReadFile(Path("campaign/master.log"));
  EXPECT_EQ(out.faults.at("store_damaged"), 1);
  EXPECT_EQ(out.faults.at("master_kill"), 3);
  EXPECT_EQ(out.faults.at("store_truncated"), 1);
  EXPECT_GE(out.jobs_submitted, 2);
  EXPECT_EQ(out.jobs_listed, out.jobs_submitted);
  EXPECT_EQ(out.byte_identical, out.jobs_submitted) << "seed " << plan.seed;
  EXPECT_EQ(out.lost + out.duplicated, 0);
}

}  // namespace
}  // namespace radfarm::testing
