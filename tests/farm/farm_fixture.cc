#include "tests/farm/farm_fixture.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "protocol/farm_secret.h"

namespace radfarm::testing {
namespace {

std::string Trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

void FarmTest::SetUp() {
  state_dir_ = dir_.File("master");
  secret_file_ = dir_.File("secret");
  control_ = state_dir_ + "/control.sock";
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::Generate();
  ASSERT_TRUE(secret.ok());
  std::ofstream(secret_file_) << secret->ToHex() << "\n";
  std::filesystem::permissions(
      secret_file_, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

ChildProcess& FarmTest::StartMaster(const std::vector<std::string>& extra) {
  const std::string addr_file = state_dir_ + "/listen.addr";
  std::error_code ec;
  std::filesystem::remove(addr_file, ec);
  std::vector<std::string> args = {RADFARMD_PATH, "--state-dir",
                                   state_dir_,    "--secret-file",
                                   secret_file_,  "--heartbeat-ms",
                                   "200",         "--agent-timeout-ms",
                                   "2000",        "--handshake-timeout-ms",
                                   "2000",        "--log-level",
                                   "debug"};
  // An ephemeral port unless the test names one (a restarted master keeps its port).
  if (std::find(extra.begin(), extra.end(), "--listen") == extra.end()) {
    args.insert(args.end(), {"--listen", "127.0.0.1:0"});
  }
  args.insert(args.end(), extra.begin(), extra.end());
  master_ = std::make_unique<ChildProcess>(args, dir_.File("master.log"));
  ++master_starts_;
  const bool up = WaitUntil(
      [&] {
        return std::filesystem::exists(addr_file) ||
               master_->WaitExit(std::chrono::milliseconds(0)).has_value();
      },
      std::chrono::seconds(60));
  EXPECT_TRUE(up && master_->running()) << master_->Log();
  master_address_ = Trim(ReadFile(addr_file));
  return *master_;
}

ChildProcess& FarmTest::StartAgent(const std::string& name, const std::vector<std::string>& extra,
                                   const std::string& secret_file) {
  std::vector<std::string> args = {RADFARM_AGENT_PATH,
                                   "--master",
                                   master_address_,
                                   "--secret-file",
                                   secret_file.empty() ? secret_file_ : secret_file,
                                   "--state-dir",
                                   dir_.File("agent-" + name),
                                   "--threads",
                                   "1",
                                   "--name",
                                   name};
  args.insert(args.end(), extra.begin(), extra.end());
  agents_.push_back(std::make_unique<ChildProcess>(args, dir_.File("agent-" + name + ".log")));
  return *agents_.back();
}

CommandResult FarmTest::Cli(const std::vector<std::string>& args) const {
  std::vector<std::string> full = {RADFARM_CLI_PATH, "--control", control_};
  full.insert(full.end(), args.begin(), args.end());
  return RunCommand(full);
}

int64_t FarmTest::Submit(const std::string& scene, const std::vector<std::string>& flags) {
  std::vector<std::string> args = {"submit", std::string(RADFARM_SOURCE_DIR "/scenes/") + scene};
  args.insert(args.end(), flags.begin(), flags.end());
  const CommandResult r = Cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err << MasterLog();
  try {
    return std::stoll(r.out);
  } catch (...) {
    ADD_FAILURE() << "submit printed '" << r.out << "'";
    return -1;
  }
}

nlohmann::json FarmTest::Status(int64_t id) const {
  const CommandResult r = Cli({"status", std::to_string(id), "--json"});
  if (r.exit_code != 0) return nullptr;
  nlohmann::json json = nlohmann::json::parse(r.out, nullptr, false);
  return json.is_discarded() ? nlohmann::json(nullptr) : json;
}

nlohmann::json FarmTest::Agents() const {
  const CommandResult r = Cli({"agents", "--json"});
  if (r.exit_code != 0) return nullptr;
  nlohmann::json json = nlohmann::json::parse(r.out, nullptr, false);
  return json.is_discarded() ? nlohmann::json(nullptr) : json;
}

bool FarmTest::WaitForState(int64_t id, const std::string& state, std::chrono::seconds timeout) {
  if (id < 0) return false;  // the submit failed and said so
  std::string last;
  const bool reached = WaitUntil(
      [&] {
        const nlohmann::json job = Status(id);
        if (job.is_object() && job.contains("state")) last = job["state"].get<std::string>();
        return last == state;
      },
      timeout);
  EXPECT_TRUE(reached) << "job " << id << " is '" << last << "', not '" << state << "'\n"
                       << MasterLog();
  return reached;
}

std::string FarmTest::FetchPatches(int64_t id) {
  const std::string out = dir_.File("fetch-" + std::to_string(id));
  const CommandResult r = Cli({"fetch", std::to_string(id), "--out", out});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return ReadFile(out + "/patches.csv");
}

std::string FarmTest::ReferencePatches(const std::string& scene,
                                       const std::vector<std::string>& flags) {
  static std::mutex mutex;
  static std::map<std::string, std::string> cache;
  std::string key = scene;
  for (const std::string& f : flags) key += " " + f;
  std::lock_guard lock(mutex);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  TempDir out;
  std::vector<std::string> args = {
      RADFARM_CLI_PATH, "render",   std::string(RADFARM_SOURCE_DIR "/scenes/") + scene,
      "--out",          out.path(), "-q"};
  args.insert(args.end(), flags.begin(), flags.end());
  const CommandResult r = RunCommand(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return cache[key] = ReadFile(out.File("patches.csv"));
}

size_t FarmTest::CountLines(const std::string& log, const std::string& text) {
  size_t count = 0;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) count += line.find(text) != std::string::npos;
  return count;
}

int64_t JobRound(const nlohmann::json& job) {
  return job.is_object() && job["round"].is_number() ? job["round"].get<int64_t>() : -1;
}

int64_t AgentLeases(const nlohmann::json& agents, const std::string& name) {
  if (!agents.is_array()) return -1;
  for (const auto& agent : agents) {
    if (agent["name"] == name) return agent["leases"].get<int64_t>();
  }
  return -1;
}

}  // namespace radfarm::testing
