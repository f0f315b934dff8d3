// office_bench: does a farm of N small office machines finish a job N times faster than one of
// them, end to end? Every process runs capped at a share of a core in a cgroup of its own
// (testing/office_emulation.h); one machine is `radfarm render --threads 1`, the farm
// radfarmd, N one-thread agents and the client, from submit to fetch done. Prints the table per
// job (N, ideal time, real time, speedup, efficiency, each part's CPU seconds), checks the outputs
// are render's byte for byte, fits T(N) = S + P/N, and writes bench/results/office_bench.json.
// See kOfficeUsage (office_options.h) for the flags.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/office/office_options.h"
#include "testing/office_emulation.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

std::string Join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

// The farm sizes whose caps, with the master's and the client's, fit in `cpus` cores.
std::vector<size_t> Fitting(const OfficeOptions& o, unsigned cpus, std::vector<size_t>* skipped) {
  std::vector<size_t> fit;
  for (size_t n : o.agents) {
    ((double(n) + 2) * o.share <= double(cpus) + 1e-9 ? fit : *skipped).push_back(n);
  }
  return fit;
}

// stats.json's patch count of an output directory; 0 when absent.
int64_t Patches(const std::string& out_dir) {
  const nlohmann::json stats =
      nlohmann::json::parse(testing::ReadFile(out_dir + "/stats.json"), nullptr, false);
  return stats.is_object() ? stats.value("patches", int64_t{0}) : 0;
}

// One job: one machine, then the farm at each size. Returns the job's JSON; counts the farm runs
// whose outputs differ from render's in *mismatches.
nlohmann::json RunJob(testing::OfficeSetup setup, const std::vector<size_t>& sizes,
                      const std::string& dir, int* mismatches) {
  std::filesystem::create_directories(dir);
  const std::string render_out = dir + "/render";
  std::printf("\njob %s %s\n", setup.job_file.c_str(), Join(setup.flags, " ").c_str());
  const testing::MachineRun one = testing::RunOneMachine(setup, render_out);
  const int64_t patches = Patches(render_out);
  std::printf("one machine (radfarm render --threads 1): %.1f s, CPU %.1f s, %lld patches\n",
              one.seconds, one.cpu_seconds, static_cast<long long>(patches));
  std::printf("%3s %8s %8s %8s %10s %8s %8s %12s %11s %11s  %s\n", "N", "ideal s", "real s",
              "speedup", "efficiency", "job s", "fetch s", "radfarmd CPU", "agents CPU",
              "client CPU", "outputs");
  nlohmann::json runs = nlohmann::json::array();
  std::vector<std::pair<double, double>> measured;
  for (size_t n : sizes) {
    const std::string farm_dir = dir + "/farm-" + std::to_string(n);
    std::filesystem::create_directories(farm_dir);
    const testing::FarmRun run = testing::RunFarm(setup, n, farm_dir, farm_dir + "/out");
    const std::vector<std::string> differing =
        testing::DifferingOutputs(render_out, farm_dir + "/out");
    *mismatches += differing.empty() ? 0 : 1;
    const double speedup = one.seconds / run.seconds;
    std::printf("%3zu %8.1f %8.1f %8.2f %9.1f%% %8.1f %8.1f %12.1f %11.1f %11.1f  %s\n", n,
                one.seconds / double(n), run.seconds, speedup, 100 * speedup / double(n),
                run.job_seconds, run.fetch_seconds, run.master_cpu, run.agents_cpu, run.client_cpu,
                differing.empty() ? "identical" : ("DIFFER: " + Join(differing, ", ")).c_str());
    std::fflush(stdout);
    measured.emplace_back(double(n), run.seconds);
    runs.push_back({{"agents", n},
                    {"ideal_seconds", one.seconds / double(n)},
                    {"seconds", run.seconds},
                    {"speedup", speedup},
                    {"efficiency", speedup / double(n)},
                    {"job_seconds", run.job_seconds},
                    {"fetch_seconds", run.fetch_seconds},
                    {"master_cpu_seconds", run.master_cpu},
                    {"agents_cpu_seconds", run.agents_cpu},
                    {"client_cpu_seconds", run.client_cpu},
                    {"differing_outputs", differing}});
  }
  const testing::AmdahlFit fit = testing::FitAmdahl(measured);
  std::printf("T(N) = %.1f s + %.1f s / N (least squares over N = measured):", fit.serial,
              fit.parallel);
  for (double n : {100.0, 1000.0}) {
    std::printf(" %g machines %.1f s (speedup %.2f);", n, fit.Predict(n),
                one.seconds / fit.Predict(n));
  }
  std::printf("\n");
  nlohmann::json predictions = nlohmann::json::array();
  for (double n : {100.0, 1000.0}) {
    predictions.push_back(
        {{"machines", n}, {"seconds", fit.Predict(n)}, {"speedup", one.seconds / fit.Predict(n)}});
  }
  return {{"job", setup.job_file},
          {"flags", setup.flags},
          {"patches", patches},
          {"one_machine", {{"seconds", one.seconds}, {"cpu_seconds", one.cpu_seconds}}},
          {"runs", runs},
          {"amdahl", {{"serial_seconds", fit.serial}, {"parallel_seconds", fit.parallel}}},
          {"predictions", predictions}};
}

int Main(int argc, char** argv) {
  OfficeOptions o;
  std::string error;
  if (!ParseOfficeOptions(argc, argv, &o, &error)) {
    std::fprintf(error.empty() ? stdout : stderr, "%s%s",
                 error.empty() ? "" : (error + "\n").c_str(), kOfficeUsage);
    return error.empty() ? 0 : 2;
  }
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  std::string why;
  const std::optional<testing::CpuController> cpu = testing::FindCpuController(&why);
  if (!cpu) {
    std::printf("office_bench: skipped: %s\n", why.c_str());
    return 0;
  }
  std::vector<size_t> skipped;
  const std::vector<size_t> sizes = Fitting(o, machine.cpus, &skipped);
  std::printf("office_bench: %u CPUs, every process capped at %.2f of a core (cgroup %s, %s)\n",
              machine.cpus, o.share,
              cpu->version == testing::CpuController::Version::kV1 ? "v1 cpu" : "v2 cpu.max",
              cpu->parent.c_str());
  for (size_t n : skipped) {
    std::printf(
        "N = %zu skipped: %zu agents, radfarmd and the client at %.2f each need %.1f "
        "cores, more than %u\n",
        n, n, o.share, (double(n) + 2) * o.share, machine.cpus);
  }
  if (sizes.empty()) throw std::runtime_error("no farm size fits: lower --share or --agents");

  std::optional<testing::TempDir> temp;
  if (o.keep.empty()) temp.emplace("office_bench");
  const std::string root = o.keep.empty() ? temp->path() : o.keep;
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json jobs = nlohmann::json::array();
  int mismatches = 0;
  for (size_t i = 0; i < o.jobs.size(); ++i) {
    const testing::OfficeSetup setup{
        *cpu,      {RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH},
        o.share,   o.timeout,
        o.jobs[i], o.flags,
        {}};
    jobs.push_back(RunJob(setup, sizes, root + "/job-" + std::to_string(i + 1), &mismatches));
  }
  const nlohmann::json out = {
      {"machine", MachineJson(machine)},
      {"load_average_end", ReadLoadAverage()},
      {"total_seconds",
       std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
      {"cgroup", cpu->version == testing::CpuController::Version::kV1 ? "v1" : "v2"},
      {"share", o.share},
      {"skipped_agents", skipped},
      {"jobs", jobs}};
  WriteJson(o.json_path, out);
  std::printf("\nwrote %s\n", o.json_path.c_str());
  if (mismatches > 0) {
    std::fprintf(stderr, "office_bench: %d farm runs wrote outputs other than render's\n",
                 mismatches);
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  try {
    return radfarm::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "office_bench: %s\n", e.what());
    return 1;
  }
}
