// FarmTest: a farm on loopback for integration tests: a real radfarmd with a temporary state
// directory and an ephemeral port, real radfarm-agent processes, and the real `radfarm` CLI talking
// to the master's control socket. Every wait polls a condition with a generous timeout.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/run_command.h"
#include "tests/farm/child_process.h"

namespace radfarm::testing {

inline constexpr auto kJobTimeout = std::chrono::seconds(240);

// A job shorter than the default Cornell box: a ray budget of a few rounds.
inline const std::vector<std::string> kShortJob = {"--rays", "3000000"};

// The round of a `Status` job object, or -1 when it has none.
int64_t JobRound(const nlohmann::json& job);
// The leases the agent called `name` holds in an `Agents` array, or -1 when it is not listed.
int64_t AgentLeases(const nlohmann::json& agents, const std::string& name);

class FarmTest : public ::testing::Test {
 protected:
  void SetUp() override;

  // Starts (or restarts) radfarmd and waits for its listen.addr. `extra` flags go last.
  ChildProcess& StartMaster(const std::vector<std::string>& extra = {});
  // Starts an agent connecting to the current master address; its state dir is agent-NAME.
  ChildProcess& StartAgent(const std::string& name, const std::vector<std::string>& extra = {},
                           const std::string& secret_file = "");

  // `radfarm --control SOCKET args...`
  CommandResult Cli(const std::vector<std::string>& args) const;
  // Submits `scene` (relative to scenes/) with extra flags; returns the job id.
  int64_t Submit(const std::string& scene, const std::vector<std::string>& flags = {});
  // `radfarm status ID --json`'s job object; null on failure.
  nlohmann::json Status(int64_t id) const;
  nlohmann::json Agents() const;
  // Waits until the job reaches `state`; fails the test (with the master's log) on timeout.
  bool WaitForState(int64_t id, const std::string& state,
                    std::chrono::seconds timeout = kJobTimeout);
  // `radfarm fetch ID --out DIR` and the bytes of DIR/patches.csv.
  std::string FetchPatches(int64_t id);
  // `radfarm render` of the same scene and flags, run once per test binary and remembered.
  static std::string ReferencePatches(const std::string& scene,
                                      const std::vector<std::string>& flags = {});

  std::string Path(const std::string& name) const { return dir_.File(name); }
  std::string MasterLog() const { return master_ ? master_->Log() : ""; }
  // Counts the lines of `log` containing `text`.
  static size_t CountLines(const std::string& log, const std::string& text);

  TempDir dir_;
  std::string state_dir_, secret_file_, control_;
  std::string master_address_;
  std::unique_ptr<ChildProcess> master_;
  std::vector<std::unique_ptr<ChildProcess>> agents_;
  int master_starts_ = 0;
};

}  // namespace radfarm::testing
