#include "testing/loopback_farm.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "protocol/farm_secret.h"
#include "testing/temp_dir.h"

namespace radfarm::testing {
namespace {

std::string Trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

nlohmann::json ParseOrNull(const CommandResult& r) {
  if (r.exit_code != 0) return nullptr;
  nlohmann::json json = nlohmann::json::parse(r.out, nullptr, false);
  return json.is_discarded() ? nlohmann::json(nullptr) : json;
}

}  // namespace

bool IsFinished(const nlohmann::json& job) {
  const std::string state = job.is_object() ? job.value("state", "") : "";
  return state == "done" || state == "failed" || state == "cancelled";
}

LoopbackFarm::LoopbackFarm(FarmPrograms programs, std::string dir)
    : programs_(std::move(programs)), dir_(std::move(dir)) {
  state_dir_ = File("master");
  secret_file_ = File("secret");
  control_ = state_dir_ + "/control.sock";
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::Generate();
  if (!secret.ok()) throw std::runtime_error("cannot make a farm secret: " + secret.error());
  secret_hex_ = secret->ToHex();
  std::ofstream(secret_file_) << secret_hex_ << "\n";
  std::filesystem::permissions(
      secret_file_, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

LoopbackFarm::~LoopbackFarm() {
  agents_.clear();
  master_.reset();
}

ChildProcess& LoopbackFarm::StartMaster(const std::vector<std::string>& flags,
                                        std::chrono::milliseconds timeout) {
  std::filesystem::create_directories(state_dir_);
  const std::string addr_file = state_dir_ + "/listen.addr";
  std::error_code ec;
  std::filesystem::remove(addr_file, ec);
  master_address_.clear();
  std::vector<std::string> args = {programs_.radfarmd, "--state-dir", state_dir_, "--secret-file",
                                   secret_file_};
  if (std::find(flags.begin(), flags.end(), "--listen") == flags.end()) {
    args.insert(args.end(), {"--listen", "127.0.0.1:0"});
  }
  args.insert(args.end(), flags.begin(), flags.end());
  master_.reset();  // a restart: the old master has been stopped or killed by the caller
  master_ = std::make_unique<ChildProcess>(args, File("master.log"), OptionsFor("master"));
  // The file is renamed into place or written at once; an empty read means "not yet".
  WaitUntil(
      [&] {
        master_address_ = Trim(ReadFile(addr_file));
        return !master_address_.empty() || !master_->running();
      },
      timeout, std::chrono::milliseconds(10));
  return *master_;
}

ChildProcess& LoopbackFarm::StartAgent(const std::string& name, unsigned threads,
                                       const std::vector<std::string>& extra,
                                       const std::string& secret_file, const std::string& master) {
  return StartAgentAs(programs_.agent, name, threads, extra, secret_file, master);
}

ChildProcess& LoopbackFarm::StartAgentProgram(const std::string& program, const std::string& name,
                                              unsigned threads,
                                              const std::vector<std::string>& extra) {
  return StartAgentAs(program, name, threads, extra, "", "");
}

ChildProcess& LoopbackFarm::StartAgentAs(const std::string& program, const std::string& name,
                                         unsigned threads, const std::vector<std::string>& extra,
                                         const std::string& secret_file,
                                         const std::string& master) {
  std::vector<std::string> args = {program,
                                   "--master",
                                   master.empty() ? master_address_ : master,
                                   "--secret-file",
                                   secret_file.empty() ? secret_file_ : secret_file,
                                   "--state-dir",
                                   File("agent-" + name),
                                   "--threads",
                                   std::to_string(threads),
                                   "--name",
                                   name};
  args.insert(args.end(), extra.begin(), extra.end());
  agents_.push_back(std::make_unique<ChildProcess>(args, File("agent-" + name + ".log"),
                                                   OptionsFor("agent-" + name)));
  return *agents_.back();
}

CommandResult LoopbackFarm::Cli(const std::vector<std::string>& args) const {
  std::vector<std::string> full = {programs_.cli, "--control", control_};
  full.insert(full.end(), args.begin(), args.end());
  ChildOptions options = OptionsFor("client");
  options.timeout = command_timeout_;
  CommandResult result = RunCommandWith(full, options);
  client_cpu_seconds_ += result.cpu_seconds;
  return result;
}

ChildOptions LoopbackFarm::OptionsFor(const std::string& role) const {
  ChildOptions options;
  if (cgroups_) options.cgroup_procs = cgroups_(role);
  return options;
}

int64_t LoopbackFarm::Submit(const std::string& job_file, const std::vector<std::string>& flags,
                             std::string* error) const {
  std::vector<std::string> args = {"submit", job_file};
  args.insert(args.end(), flags.begin(), flags.end());
  const CommandResult r = Cli(args);
  if (r.exit_code != 0) {
    *error = "radfarm submit " + job_file + " failed: " + r.err;
    return -1;
  }
  try {
    return std::stoll(r.out);
  } catch (...) {
    *error = "radfarm submit printed '" + r.out + "'";
    return -1;
  }
}

nlohmann::json LoopbackFarm::Status(int64_t id) const {
  return ParseOrNull(Cli({"status", std::to_string(id), "--json"}));
}

nlohmann::json LoopbackFarm::Agents() const { return ParseOrNull(Cli({"agents", "--json"})); }

CommandResult LoopbackFarm::Fetch(int64_t id, const std::string& out_dir) const {
  return Cli({"fetch", std::to_string(id), "--out", out_dir});
}

bool LoopbackFarm::WaitForAgents(size_t count, std::chrono::milliseconds timeout) const {
  return WaitUntil(
      [&] {
        const nlohmann::json agents = Agents();
        return agents.is_array() && agents.size() >= count;
      },
      timeout, std::chrono::milliseconds(50));
}

nlohmann::json LoopbackFarm::WaitForJob(int64_t id,
                                        const std::function<bool(const nlohmann::json&)>& until,
                                        std::chrono::milliseconds timeout,
                                        std::chrono::milliseconds poll) const {
  nlohmann::json last = nullptr;
  WaitUntil(
      [&] {
        nlohmann::json job = Status(id);
        if (job.is_object()) last = std::move(job);
        return last.is_object() && until(last);
      },
      timeout, poll);
  return last;
}

}  // namespace radfarm::testing
