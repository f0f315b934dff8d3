// LoopbackFarm: a farm on loopback for integration tests and farm_bench: a real radfarmd with its
// own state directory, a fresh farm secret and an ephemeral port (`--listen 127.0.0.1:0`, the port
// read back from STATE/listen.addr), real radfarm-agent processes, and the real `radfarm` CLI
// talking to the master's control socket. Every wait polls a condition with a timeout.
//
// Failures are returned, not thrown or asserted: GoogleTest fixtures (tests/farm/farm_fixture.h)
// turn them into test failures, farm_bench into exceptions. Not thread-safe: one thread drives it.
// The destructor kills every process it started, agents first.
//
//   LoopbackFarm farm({RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, dir.path());
//   farm.StartMaster({"--log-level", "warning"});
//   farm.StartAgent("a", 2);
//   farm.WaitForAgents(1, std::chrono::seconds(60));
//   const int64_t id = farm.Submit("scenes/cornell-box.toml", {}, &error);
//   const nlohmann::json job = farm.WaitForJob(id, IsFinished, std::chrono::seconds(600));
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "testing/child_process.h"

namespace radfarm::testing {

struct FarmPrograms {
  std::string radfarmd, agent, cli;
};

// Whether a `Status` job object is in a state it never leaves by itself (done, failed, cancelled).
bool IsFinished(const nlohmann::json& job);

class LoopbackFarm {
 public:
  // `dir` must exist; the farm keeps all its files there (master/, agent-NAME/, *.log, secret).
  // Throws std::runtime_error when the secret cannot be made.
  LoopbackFarm(FarmPrograms programs, std::string dir);
  ~LoopbackFarm();
  LoopbackFarm(const LoopbackFarm&) = delete;
  LoopbackFarm& operator=(const LoopbackFarm&) = delete;

  // Starts (or restarts) radfarmd and waits up to `timeout` for its listen.addr. `flags` go last;
  // without a `--listen` among them the master listens on an ephemeral port. Afterwards
  // master_address() is empty if the master did not come up (see MasterLog()).
  ChildProcess& StartMaster(const std::vector<std::string>& flags = {},
                            std::chrono::milliseconds timeout = std::chrono::seconds(60));
  // Starts radfarm-agent NAME (state dir agent-NAME) with `threads` threads against the current
  // master address (or `master`, e.g. a proxy's, if not empty); `extra` flags go last. An empty
  // `secret_file` means the farm's.
  ChildProcess& StartAgent(const std::string& name, unsigned threads,
                           const std::vector<std::string>& extra = {},
                           const std::string& secret_file = "", const std::string& master = "");
  // StartAgent with another agent binary (tests/farm's radfarm-lying-agent) in place of
  // FarmPrograms::agent.
  ChildProcess& StartAgentProgram(const std::string& program, const std::string& name,
                                  unsigned threads, const std::vector<std::string>& extra = {});

  // `radfarm --control SOCKET args...`
  CommandResult Cli(const std::vector<std::string>& args) const;
  // `radfarm submit JOB_FILE FLAGS...`: the job id, or -1 with the reason in *error.
  int64_t Submit(const std::string& job_file, const std::vector<std::string>& flags,
                 std::string* error) const;
  // `radfarm status ID --json`'s job object; null on failure.
  nlohmann::json Status(int64_t id) const;
  // `radfarm agents --json`'s array; null on failure.
  nlohmann::json Agents() const;
  // `radfarm fetch ID --out DIR`.
  CommandResult Fetch(int64_t id, const std::string& out_dir) const;

  // Polls `radfarm agents` every 50 ms until at least `count` agents are connected.
  bool WaitForAgents(size_t count, std::chrono::milliseconds timeout) const;
  // Polls the job's status every `poll` until `until` holds for it or `timeout` passes; returns
  // the last job object read (null if none could be read).
  nlohmann::json WaitForJob(int64_t id, const std::function<bool(const nlohmann::json&)>& until,
                            std::chrono::milliseconds timeout,
                            std::chrono::milliseconds poll = std::chrono::milliseconds(20)) const;

  // Runs each process the farm starts from now on in a cgroup (testing/cpu_cap.h): `procs(role)`
  // gives the `cgroup.procs` file for "master", "agent-NAME" or "client" (every radfarm command),
  // or "" for this process's own group.
  void set_cgroups(std::function<std::string(const std::string& role)> procs) {
    cgroups_ = std::move(procs);
  }
  // Each radfarm command is SIGKILLed after `timeout` (zero, the default: none).
  void set_command_timeout(std::chrono::milliseconds timeout) { command_timeout_ = timeout; }
  // CPU seconds (user + system) of every radfarm command run so far: the client's work.
  double client_cpu_seconds() const { return client_cpu_seconds_; }

  const std::string& dir() const { return dir_; }
  std::string File(const std::string& name) const { return dir_ + "/" + name; }
  const std::string& state_dir() const { return state_dir_; }
  const std::string& secret_file() const { return secret_file_; }
  const std::string& secret_hex() const { return secret_hex_; }
  const std::string& control() const { return control_; }
  const std::string& master_address() const { return master_address_; }
  // The current master; null before StartMaster.
  ChildProcess* master() const { return master_.get(); }
  std::string MasterLog() const { return master_ ? master_->Log() : ""; }

 private:
  ChildProcess& StartAgentAs(const std::string& program, const std::string& name, unsigned threads,
                             const std::vector<std::string>& extra, const std::string& secret_file,
                             const std::string& master);
  ChildOptions OptionsFor(const std::string& role) const;
  FarmPrograms programs_;
  std::function<std::string(const std::string&)> cgroups_;
  std::chrono::milliseconds command_timeout_{0};
  mutable double client_cpu_seconds_ = 0;  // summed by the const Cli
  std::string dir_, state_dir_, secret_file_, secret_hex_, control_;
  std::string master_address_;
  std::unique_ptr<ChildProcess> master_;
  std::vector<std::unique_ptr<ChildProcess>> agents_;
};

}  // namespace radfarm::testing
