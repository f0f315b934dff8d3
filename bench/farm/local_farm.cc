#include "bench/farm/local_farm.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "protocol/farm_secret.h"

namespace radfarm::bench {
namespace {

std::string Trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// The last lines of a log, for error messages.
std::string Tail(const std::string& text, size_t lines = 15) {
  size_t pos = text.size();
  for (size_t n = 0; n <= lines && pos > 0; ++n) pos = text.rfind('\n', pos - 1);
  return pos == std::string::npos ? text : text.substr(pos + 1);
}

}  // namespace

LocalFarm::LocalFarm(FarmPrograms programs, std::string dir)
    : programs_(std::move(programs)), dir_(std::move(dir)) {
  state_dir_ = dir_ + "/master";
  secret_file_ = dir_ + "/secret";
  control_ = state_dir_ + "/control.sock";
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::Generate();
  if (!secret) throw std::runtime_error("cannot make a farm secret: " + secret.error());
  secret_hex_ = secret->ToHex();
  std::ofstream(secret_file_) << secret_hex_ << "\n";
  std::filesystem::permissions(
      secret_file_, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

LocalFarm::~LocalFarm() {
  for (auto& agent : agents_) agent->Stop(std::chrono::seconds(2));
  if (master_) master_->Stop(std::chrono::seconds(5));
}

void LocalFarm::Fail(const std::string& what) {
  const std::string log = master_ ? ReadFile(master_->log_path()) : "";
  throw std::runtime_error(what + (log.empty() ? "" : "\nmaster log (tail):\n" + Tail(log)));
}

void LocalFarm::StartMaster(const std::vector<std::string>& extra) {
  std::filesystem::create_directories(state_dir_);
  const std::string addr_file = state_dir_ + "/listen.addr";
  std::vector<std::string> args = {programs_.radfarmd, "--state-dir", state_dir_,
                                   "--secret-file",    secret_file_,  "--listen",
                                   "127.0.0.1:0",      "--log-level", "warning"};
  args.insert(args.end(), extra.begin(), extra.end());
  master_ = std::make_unique<ChildProcess>(args, dir_ + "/master.log");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(addr_file)) {
    if (!master_->running()) Fail("radfarmd exited at start");
    if (std::chrono::steady_clock::now() > deadline) Fail("radfarmd wrote no listen.addr");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // The file is renamed into place or written at once; an empty read means "not yet".
  while ((master_address_ = Trim(ReadFile(addr_file))).empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void LocalFarm::StartAgent(const std::string& name, unsigned threads) {
  const std::vector<std::string> args = {programs_.agent,
                                         "--master",
                                         master_address_,
                                         "--secret-file",
                                         secret_file_,
                                         "--state-dir",
                                         dir_ + "/agent-" + name,
                                         "--threads",
                                         std::to_string(threads),
                                         "--name",
                                         name};
  agents_.push_back(std::make_unique<ChildProcess>(args, dir_ + "/agent-" + name + ".log"));
}

CommandOutput LocalFarm::Cli(const std::vector<std::string>& args) {
  std::vector<std::string> full = {programs_.cli, "--control", control_};
  full.insert(full.end(), args.begin(), args.end());
  return RunCommand(full, dir_);
}

void LocalFarm::WaitForAgents(size_t count, std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    const CommandOutput r = Cli({"agents", "--json"});
    if (r.exit_code == 0) {
      const nlohmann::json agents = nlohmann::json::parse(r.out, nullptr, false);
      if (agents.is_array() && agents.size() >= count) return;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      Fail("fewer than " + std::to_string(count) + " agents connected");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

int64_t LocalFarm::Submit(const std::string& job_file, const std::vector<std::string>& flags) {
  std::vector<std::string> args = {"submit", job_file};
  args.insert(args.end(), flags.begin(), flags.end());
  const CommandOutput r = Cli(args);
  if (r.exit_code != 0) Fail("radfarm submit " + job_file + " failed: " + r.err);
  return std::stoll(r.out);
}

nlohmann::json LocalFarm::Status(int64_t id) {
  const CommandOutput r = Cli({"status", std::to_string(id), "--json"});
  if (r.exit_code != 0) Fail("radfarm status " + std::to_string(id) + " failed: " + r.err);
  nlohmann::json job = nlohmann::json::parse(r.out, nullptr, false);
  if (!job.is_object()) Fail("radfarm status printed no job object: " + r.out);
  return job;
}

nlohmann::json LocalFarm::WaitDone(int64_t id, std::chrono::seconds timeout,
                                   std::chrono::milliseconds poll) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    nlohmann::json job = Status(id);
    const std::string state = job.value("state", "");
    if (state == "done") return job;
    if (state == "failed" || state == "cancelled") {
      Fail("job " + std::to_string(id) + " ended " + state + ": " + job.dump());
    }
    if (std::chrono::steady_clock::now() > deadline) {
      Fail("job " + std::to_string(id) + " is still " + state + " after " +
           std::to_string(timeout.count()) + " s");
    }
    std::this_thread::sleep_for(poll);
  }
}

void LocalFarm::Fetch(int64_t id, const std::string& out_dir) {
  const CommandOutput r = Cli({"fetch", std::to_string(id), "--out", out_dir});
  if (r.exit_code != 0) Fail("radfarm fetch " + std::to_string(id) + " failed: " + r.err);
}

}  // namespace radfarm::bench
