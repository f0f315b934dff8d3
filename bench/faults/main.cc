// fault_bench: a long fault campaign (testing/fault_campaign.h) on the loopback farm: agents
// SIGKILLed, SIGSTOPped and restarted, the master SIGKILLed and restarted on its state and port,
// the state directory (a tmpfs) filled to ENOSPC and freed, a damaged store file refused at start,
// the store file cut short before a master restart, while jobs run; then every job is checked
// against `radfarm render`. Prints the counts and writes bench/results/fault_bench.json;
// docs/BENCHMARKS-faults.md keeps the table. Needs root for the tmpfs (or --disk-fills 0). The seed
// is printed; --seed N re-runs a campaign.
//
//   fault_bench [--seed N] [--agents 3] [--jobs 8] [--agent-faults 100] [--master-kills 30]
//               [--disk-fills 5] [--store-truncations 5] [--patch-size MM] [--rays N]
//               [--json PATH]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/run_benchmark.h"
#include "testing/fault_campaign.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

using testing::FaultPlan;

struct Options {
  FaultPlan plan;
  std::string patch_size;  // empty: the scene's default
  std::string rays = "6000000";
  std::string json = DefaultJsonPath("fault_bench");
};

Options Parse(int argc, char** argv) {
  Options o;
  o.plan.seed = std::random_device{}();
  o.plan.agents = 3;
  o.plan.jobs = 8;
  o.plan.agent_faults = 100;
  o.plan.master_kills = 30;
  o.plan.disk_fills = 5;
  o.plan.store_truncations = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--seed") {
      o.plan.seed = uint32_t(std::stoul(next()));
    } else if (a == "--agents") {
      o.plan.agents = unsigned(std::stoul(next()));
    } else if (a == "--jobs") {
      o.plan.jobs = std::stoi(next());
    } else if (a == "--agent-faults") {
      o.plan.agent_faults = std::stoi(next());
    } else if (a == "--master-kills") {
      o.plan.master_kills = std::stoi(next());
    } else if (a == "--disk-fills") {
      o.plan.disk_fills = std::stoi(next());
    } else if (a == "--store-truncations") {
      o.plan.store_truncations = std::stoi(next());
    } else if (a == "--patch-size") {
      o.patch_size = next();
    } else if (a == "--rays") {
      o.rays = next();
    } else if (a == "--json") {
      o.json = next();
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "fault_bench [--seed N] [--agents 3] [--jobs 8] [--agent-faults 100]\n"
          "            [--master-kills 30] [--disk-fills 5] [--store-truncations 5]\n"
          "            [--patch-size MM] [--rays 6000000] [--json PATH]\n"
          "  A seeded fault campaign against a loopback farm rendering the Cornell box; every\n"
          "  job is checked against `radfarm render`. --disk-fills needs root (a tmpfs).\n");
      std::exit(0);
    } else {
      throw std::runtime_error("unknown argument " + a + " (see --help)");
    }
  }
  return o;
}

int Run(int argc, char** argv) {
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  Options o = Parse(argc, argv);
  FaultPlan& plan = o.plan;
  plan.job_file = RADFARM_SOURCE_DIR "/scenes/cornell-box.toml";
  plan.job_flags = {"--rays", o.rays};
  if (!o.patch_size.empty())
    plan.job_flags.insert(plan.job_flags.end(), {"--patch-size", o.patch_size});
  plan.master_flags = {
      "--heartbeat-ms",  "200", "--agent-timeout-ms", "2000", "--handshake-timeout-ms", "2000",
      "--hold-retry-ms", "200", "--log-level",        "info"};
  std::printf("fault_bench seed %u (--seed %u re-runs this campaign)\n", plan.seed, plan.seed);

  testing::TempDir dir("fault-bench");
  std::vector<std::string> render = {RADFARM_CLI_PATH, "render",           plan.job_file,
                                     "--out",          dir.File("render"), "-q"};
  render.insert(render.end(), plan.job_flags.begin(), plan.job_flags.end());
  const testing::CommandResult r = testing::RunCommand(render);
  if (r.exit_code != 0) throw std::runtime_error("radfarm render failed: " + r.err);
  const std::string reference = testing::ReadFile(dir.File("render/patches.csv"));

  std::filesystem::create_directories(dir.File("farm"));
  const testing::CampaignOutcome out = testing::RunFaultCampaign(
      {RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, dir.File("farm"), plan, reference,
      [](const std::string& line) { std::printf("  %s\n", line.c_str()); });

  std::printf("\n%-28s %8s\n", "fault", "count");
  for (const auto& [kind, count] : out.faults) std::printf("%-28s %8d\n", kind.c_str(), count);
  std::printf("\n%-28s %8s\n", "jobs", "count");
  const std::pair<const char*, int> jobs[] = {{"submitted", out.jobs_submitted},
                                              {"listed", out.jobs_listed},
                                              {"byte-identical to render", out.byte_identical},
                                              {"failed with a message", out.failed_with_message},
                                              {"done with other bytes", out.wrong_bytes},
                                              {"unfinished", out.unfinished},
                                              {"lost", out.lost},
                                              {"duplicated", out.duplicated}};
  for (const auto& [what, count] : jobs) std::printf("%-28s %8d\n", what, count);
  std::printf("\nwall time %.1f s, seed %u: %s\n", out.wall_seconds, plan.seed,
              out.ok() ? "every invariant held" : "INVARIANTS BROKEN");

  nlohmann::json json{{"machine", MachineJson(machine)},
                      {"seed", plan.seed},
                      {"scene", "scenes/cornell-box.toml"},
                      {"job_flags", plan.job_flags},
                      {"agents", plan.agents},
                      {"faults", out.faults},
                      {"jobs_submitted", out.jobs_submitted},
                      {"jobs_listed", out.jobs_listed},
                      {"byte_identical", out.byte_identical},
                      {"failed_with_message", out.failed_with_message},
                      {"wrong_bytes", out.wrong_bytes},
                      {"unfinished", out.unfinished},
                      {"lost", out.lost},
                      {"duplicated", out.duplicated},
                      {"wall_seconds", out.wall_seconds},
                      {"problems", out.problems},
                      {"ok", out.ok()}};
  WriteJson(o.json, json);
  std::printf("wrote %s\n", o.json.c_str());
  return out.ok() ? 0 : 1;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  return radfarm::bench::RunBenchmark("fault_bench", radfarm::bench::Run, argc, argv);
}
