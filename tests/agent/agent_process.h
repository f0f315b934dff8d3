// AgentProcess: the real radfarm-agent binary (RADFARM_AGENT_PATH) as a child process, with its
// stderr (the log) captured in a file the test can read while it runs. The destructor kills the
// child with SIGKILL if it is still running and reaps it.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "testing/child_process.h"
#include "testing/temp_dir.h"
#include "tests/agent/fake_master.h"

namespace radfarm::agent::testing {

class AgentProcess {
 public:
  // Starts RADFARM_AGENT_PATH with `args` (not including the program).
  explicit AgentProcess(const std::vector<std::string>& args);
  AgentProcess(const AgentProcess&) = delete;
  AgentProcess& operator=(const AgentProcess&) = delete;

  // Everything the agent has logged so far.
  std::string Log() const { return process_.Log(); }
  // Waits until the log holds `text` at least `count` times.
  bool WaitForLog(const std::string& text, int count = 1,
                  std::chrono::milliseconds timeout = kWaitTimeout) const;
  int CountInLog(const std::string& text) const;

  void Signal(int signum) { process_.Signal(signum); }
  // The exit code (128 + signal if killed by one), once it exits; nullopt after `timeout`.
  std::optional<int> WaitExit(std::chrono::milliseconds timeout = kWaitTimeout) {
    return process_.WaitExit(timeout);
  }
  // Whether the process is still running (reaps it if it has exited).
  bool Running() { return process_.running(); }

 private:
  ::radfarm::testing::TempDir dir_;  // holds the log; declared first, so it outlives the process
  ::radfarm::testing::ChildProcess process_;
};

// A fresh directory under the temp dir, removed with its contents by the destructor.
using ScratchDir = ::radfarm::testing::TempDir;

void WriteTextFile(const std::string& path, const std::string& text);
std::string ReadTextFile(const std::string& path);

}  // namespace radfarm::agent::testing
