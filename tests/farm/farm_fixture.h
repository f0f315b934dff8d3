// FarmTest: the loopback farm (testing/loopback_farm.h) as a GoogleTest fixture: a real radfarmd
// with a temporary state directory, an ephemeral port and short heartbeat and timeout settings,
// real radfarm-agent processes, and the real `radfarm` CLI. Failures become test failures that
// show the master's log.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "testing/child_process.h"
#include "testing/loopback_farm.h"
#include "testing/temp_dir.h"

namespace radfarm::testing {

inline constexpr auto kJobTimeout = std::chrono::seconds(240);

// A job shorter than the default Cornell box: a ray budget of a few rounds.
inline const std::vector<std::string> kShortJob = {"--rays", "3000000"};

// The files `radfarm render` and `radfarm fetch` write alike, byte for byte.
inline const std::vector<std::string> kComparedOutputs = {"patches.csv", "image.png", "image.exr",
                                                          "radiosity.ply", "lit.glb"};

// The round of a `Status` job object, or -1 when it has none.
int64_t JobRound(const nlohmann::json& job);
// The leases the agent called `name` holds in an `Agents` array, or -1 when it is not listed.
int64_t AgentLeases(const nlohmann::json& agents, const std::string& name);

class FarmTest : public ::testing::Test {
 protected:
  FarmTest();

  // Starts (or restarts) radfarmd and waits for its listen.addr. `extra` flags go last.
  ChildProcess& StartMaster(const std::vector<std::string>& extra = {});
  // Starts a one-thread agent connecting to the current master address; its state dir is
  // agent-NAME.
  ChildProcess& StartAgent(const std::string& name, const std::vector<std::string>& extra = {},
                           const std::string& secret_file = "");

  // `radfarm --control SOCKET args...`
  CommandResult Cli(const std::vector<std::string>& args) const { return farm_.Cli(args); }
  // Submits `scene` (relative to scenes/) with extra flags; returns the job id.
  int64_t Submit(const std::string& scene, const std::vector<std::string>& flags = {});
  // `radfarm status ID --json`'s job object; null on failure.
  nlohmann::json Status(int64_t id) const { return farm_.Status(id); }
  nlohmann::json Agents() const { return farm_.Agents(); }
  // Waits until the job reaches `state`; fails the test (with the master's log) on timeout.
  bool WaitForState(int64_t id, const std::string& state,
                    std::chrono::seconds timeout = kJobTimeout);
  // `radfarm fetch ID --out DIR` and the bytes of DIR/patches.csv.
  std::string FetchPatches(int64_t id);
  // `radfarm render` of the same scene and flags, run once per test binary and remembered.
  static std::string ReferencePatches(const std::string& scene,
                                      const std::vector<std::string>& flags = {});
  // The files both write (kComparedOutputs, stats.json aside: it holds times), by name:
  // `radfarm fetch ID`'s into DIR (`out`, relative to the test's directory) and render's.
  std::map<std::string, std::string> FetchOutputs(int64_t id, const std::string& out);
  static const std::map<std::string, std::string>& ReferenceOutputs(
      const std::string& scene, const std::vector<std::string>& flags = {});

  std::string Path(const std::string& name) const { return dir_.File(name); }
  std::string MasterLog() const { return farm_.MasterLog(); }
  ChildProcess& master() { return *farm_.master(); }
  const std::string& master_address() const { return farm_.master_address(); }
  const std::string& control() const { return farm_.control(); }
  // Counts the lines of `log` containing `text`.
  static size_t CountLines(const std::string& log, const std::string& text);
  // Counts the lines of `log` containing both `a` and `b`.
  static size_t CountLinesWithBoth(const std::string& log, const std::string& a,
                                   const std::string& b);

  TempDir dir_;
  LoopbackFarm farm_;
};

}  // namespace radfarm::testing
