#include "testing/office_emulation.h"

#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm::testing {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The last lines of a log, for error messages.
std::string Tail(const std::string& text, size_t lines = 15) {
  size_t pos = text.size();
  for (size_t n = 0; n <= lines && pos > 0; ++n) pos = text.rfind('\n', pos - 1);
  return pos == std::string::npos ? text : text.substr(pos + 1);
}

[[noreturn]] void Fail(const testing::LoopbackFarm& farm, const std::string& what) {
  const std::string log = farm.MasterLog();
  throw std::runtime_error(what + (log.empty() ? "" : "\nmaster log (tail):\n" + Tail(log)));
}

std::string Describe(const testing::CommandResult& r, std::chrono::seconds timeout) {
  return r.timed_out ? "killed after " + std::to_string(timeout.count()) + " s"
                     : "exit " + std::to_string(r.exit_code) + ": " + Tail(r.err);
}

// The CPU seconds of a process so far; 0 once it is gone.
double CpuOf(const testing::ChildProcess& process) {
  return testing::ProcessCpuSeconds(process.pid()).value_or(0);
}

}  // namespace

MachineRun RunOneMachine(const OfficeSetup& setup, const std::string& out_dir) {
  const testing::CpuGroup group(setup.cpu, "render", setup.share);
  std::vector<std::string> args = {
      setup.programs.cli, "render", setup.job_file, "--threads", "1", "--out", out_dir};
  args.insert(args.end(), setup.flags.begin(), setup.flags.end());
  const Clock::time_point start = Clock::now();
  const testing::CommandResult r =
      testing::RunCommandWith(args, {.cgroup_procs = group.procs_path(), .timeout = setup.timeout});
  const double seconds = SecondsSince(start);
  if (r.exit_code != 0 || r.timed_out) {
    throw std::runtime_error("radfarm render " + setup.job_file + ": " +
                             Describe(r, setup.timeout));
  }
  return {seconds, r.cpu_seconds};
}

FarmRun RunFarm(const OfficeSetup& setup, size_t agents, const std::string& dir,
                const std::string& out_dir) {
  // The groups outlive the farm (declared first): its destructor kills the processes, then the
  // groups are removed.
  std::vector<std::unique_ptr<testing::CpuGroup>> groups;
  std::map<std::string, std::string> procs;
  const auto add_group = [&](const std::string& role) {
    groups.push_back(std::make_unique<testing::CpuGroup>(setup.cpu, role, setup.share));
    procs[role] = groups.back()->procs_path();
  };
  add_group("master");
  add_group("client");
  std::vector<std::string> names;
  for (size_t i = 0; i < agents; ++i) {
    names.push_back("a" + std::to_string(i + 1));
    add_group("agent-" + names.back());
  }
  testing::LoopbackFarm farm(setup.programs, dir);
  farm.set_cgroups([&procs](const std::string& role) {
    const auto it = procs.find(role);
    return it == procs.end() ? std::string() : it->second;
  });
  farm.set_command_timeout(setup.timeout);
  std::vector<std::string> master_flags = {"--log-level", "warning"};
  master_flags.insert(master_flags.end(), setup.master_flags.begin(), setup.master_flags.end());
  testing::ChildProcess& master = farm.StartMaster(master_flags);
  if (farm.master_address().empty()) Fail(farm, "radfarmd wrote no listen.addr");
  std::vector<testing::ChildProcess*> agent_processes;
  for (const std::string& name : names) agent_processes.push_back(&farm.StartAgent(name, 1));
  if (!farm.WaitForAgents(agents, std::chrono::seconds(120))) {
    Fail(farm, "fewer than " + std::to_string(agents) + " agents connected");
  }

  const auto agents_cpu = [&] {
    double sum = 0;
    for (const testing::ChildProcess* a : agent_processes) sum += CpuOf(*a);
    return sum;
  };
  FarmRun run;
  run.agents = agents;
  const double master_before = CpuOf(master), agents_before = agents_cpu();
  const double client_before = farm.client_cpu_seconds();
  const Clock::time_point start = Clock::now();
  std::string error;
  const int64_t id = farm.Submit(setup.job_file, setup.flags, &error);
  if (id < 0) Fail(farm, error);
  const nlohmann::json job =
      farm.WaitForJob(id, testing::IsFinished, setup.timeout, std::chrono::milliseconds(250));
  run.job_seconds = SecondsSince(start);
  const std::string state = job.is_object() ? job.value("state", "") : "";
  if (state != "done") {
    Fail(farm, "job " + std::to_string(id) + " is " + (state.empty() ? "unknown" : state) +
                   " after " + std::to_string(int(run.job_seconds)) + " s");
  }
  const Clock::time_point fetch_start = Clock::now();
  const testing::CommandResult fetched = farm.Fetch(id, out_dir);
  run.fetch_seconds = SecondsSince(fetch_start);
  run.seconds = SecondsSince(start);
  if (fetched.exit_code != 0 || fetched.timed_out) {
    Fail(farm, "radfarm fetch " + std::to_string(id) + ": " + Describe(fetched, setup.timeout));
  }
  run.master_cpu = CpuOf(master) - master_before;
  run.agents_cpu = agents_cpu() - agents_before;
  run.client_cpu = farm.client_cpu_seconds() - client_before;
  return run;
}

std::vector<std::string> DifferingOutputs(const std::string& a_dir, const std::string& b_dir) {
  std::vector<std::string> differing;
  for (const std::string& name : kComparedOutputs) {
    const std::string a = a_dir + "/" + name, b = b_dir + "/" + name;
    if (!std::filesystem::exists(a) || !std::filesystem::exists(b) ||
        testing::ReadFile(a) != testing::ReadFile(b)) {
      differing.push_back(name);
    }
  }
  return differing;
}

AmdahlFit FitAmdahl(const std::vector<std::pair<double, double>>& n_and_seconds) {
  AmdahlFit fit;
  if (n_and_seconds.empty()) return fit;
  if (n_and_seconds.size() == 1) {
    fit.parallel = n_and_seconds[0].first * n_and_seconds[0].second;
    return fit;
  }
  // Linear least squares of T against x = 1/N.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [n, seconds] : n_and_seconds) {
    const double x = 1.0 / n;
    sx += x;
    sy += seconds;
    sxx += x * x;
    sxy += x * seconds;
  }
  const double count = double(n_and_seconds.size());
  const double denominator = count * sxx - sx * sx;
  fit.parallel = denominator != 0 ? (count * sxy - sx * sy) / denominator : 0;
  fit.serial = (sy - fit.parallel * sx) / count;
  return fit;
}

}  // namespace radfarm::testing
