#include "tests/farm/farm_fixture.h"

#include <map>
#include <mutex>
#include <sstream>

namespace radfarm::testing {
namespace {

// Short heartbeats and timeouts, so that tests of lost agents and handshakes take seconds.
const std::vector<std::string> kMasterFlags = {
    "--heartbeat-ms", "200", "--agent-timeout-ms", "2000", "--handshake-timeout-ms", "2000",
    "--log-level", "debug",
    // Rounds here last a second or two: keep their results from the start, so the restart tests
    // find them (the 5 s default is KeepsRoundResultTest's).
    "--keep-results-after", "0"};

}  // namespace

FarmTest::FarmTest() : farm_({RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, dir_.path()) {}

ChildProcess& FarmTest::StartMaster(const std::vector<std::string>& extra) {
  std::vector<std::string> flags = kMasterFlags;
  flags.insert(flags.end(), extra.begin(), extra.end());
  ChildProcess& master = farm_.StartMaster(flags);
  EXPECT_TRUE(!farm_.master_address().empty() && master.running()) << master.Log();
  return master;
}

ChildProcess& FarmTest::StartAgent(const std::string& name, const std::vector<std::string>& extra,
                                   const std::string& secret_file) {
  return farm_.StartAgent(name, 1, extra, secret_file);
}

int64_t FarmTest::Submit(const std::string& scene, const std::vector<std::string>& flags) {
  std::string error;
  const int64_t id =
      farm_.Submit(std::string(RADFARM_SOURCE_DIR "/scenes/") + scene, flags, &error);
  EXPECT_GE(id, 0) << error << MasterLog();
  return id;
}

bool FarmTest::WaitForState(int64_t id, const std::string& state, std::chrono::seconds timeout) {
  if (id < 0) return false;  // the submit failed and said so
  const nlohmann::json job = farm_.WaitForJob(
      id, [&](const nlohmann::json& j) { return j.value("state", "") == state; }, timeout);
  const std::string last = job.is_object() ? job.value("state", "") : "";
  EXPECT_EQ(last, state) << "job " << id << " is '" << last << "', not '" << state << "'\n"
                         << MasterLog();
  return last == state;
}

std::string FarmTest::FetchPatches(int64_t id) {
  const std::string out = dir_.File("fetch-" + std::to_string(id));
  const CommandResult r = farm_.Fetch(id, out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return ReadFile(out + "/patches.csv");
}

std::string FarmTest::ReferencePatches(const std::string& scene,
                                       const std::vector<std::string>& flags) {
  return ReferenceOutputs(scene, flags).at("patches.csv");
}

std::map<std::string, std::string> FarmTest::FetchOutputs(int64_t id, const std::string& out) {
  const CommandResult r = farm_.Fetch(id, dir_.File(out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, std::string> files;
  for (const std::string& f : kComparedOutputs) files[f] = ReadFile(dir_.File(out) + "/" + f);
  return files;
}

const std::map<std::string, std::string>& FarmTest::ReferenceOutputs(
    const std::string& scene, const std::vector<std::string>& flags) {
  static std::mutex mutex;
  static std::map<std::string, std::map<std::string, std::string>> cache;
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
  std::map<std::string, std::string>& files = cache[key];
  for (const std::string& f : kComparedOutputs) files[f] = ReadFile(out.File(f));
  return files;
}

size_t FarmTest::CountLines(const std::string& log, const std::string& text) {
  size_t count = 0;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) count += line.find(text) != std::string::npos;
  return count;
}

size_t FarmTest::CountLinesWithBoth(const std::string& log, const std::string& a,
                                    const std::string& b) {
  size_t count = 0;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    count += line.find(a) != std::string::npos && line.find(b) != std::string::npos;
  }
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
