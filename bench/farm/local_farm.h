// LocalFarm: a farm on loopback for farm_bench, started as tests/farm/farm_fixture.cc does: a real
// radfarmd with its own state directory, a fresh farm secret and `--listen 127.0.0.1:0` (the port
// is read back from STATE/listen.addr), real radfarm-agent processes, and the real `radfarm` CLI
// talking to the master's control socket. The destructor stops every process it started.
//
// Not thread-safe: one thread drives it. Every method that talks to the master runs the CLI.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/farm/child_process.h"

namespace radfarm::bench {

struct FarmPrograms {
  std::string radfarmd, agent, cli;
};

class LocalFarm {
 public:
  // `dir` must exist and be empty; the farm keeps all its files there.
  LocalFarm(FarmPrograms programs, std::string dir);
  ~LocalFarm();
  LocalFarm(const LocalFarm&) = delete;
  LocalFarm& operator=(const LocalFarm&) = delete;

  // Starts radfarmd and waits for its listen.addr. `extra` flags go last. Throws on failure.
  void StartMaster(const std::vector<std::string>& extra = {});
  // Starts radfarm-agent NAME with `threads` threads against the master.
  void StartAgent(const std::string& name, unsigned threads);
  // Waits until `count` agents are connected (`radfarm agents --json`). Throws on timeout.
  void WaitForAgents(size_t count, std::chrono::seconds timeout = std::chrono::seconds(60));

  // `radfarm submit JOB_FILE FLAGS...`; the job id. Throws on failure.
  int64_t Submit(const std::string& job_file, const std::vector<std::string>& flags = {});
  // `radfarm status ID --json`'s job object. Throws on failure.
  nlohmann::json Status(int64_t id);
  // Polls the job every `poll` until it is done; throws if it fails, is cancelled, or takes longer
  // than `timeout`.
  nlohmann::json WaitDone(int64_t id, std::chrono::seconds timeout,
                          std::chrono::milliseconds poll = std::chrono::milliseconds(50));
  // `radfarm fetch ID --out DIR`. Throws on failure.
  void Fetch(int64_t id, const std::string& out_dir);

  const std::string& master_address() const { return master_address_; }
  const std::string& secret_hex() const { return secret_hex_; }
  pid_t master_pid() const { return master_ ? master_->pid() : -1; }
  const std::string& dir() const { return dir_; }

 private:
  CommandOutput Cli(const std::vector<std::string>& args);
  [[noreturn]] void Fail(const std::string& what);

  FarmPrograms programs_;
  std::string dir_, state_dir_, secret_file_, control_, secret_hex_;
  std::string master_address_;
  std::unique_ptr<ChildProcess> master_;
  std::vector<std::unique_ptr<ChildProcess>> agents_;
};

}  // namespace radfarm::bench
