// Child processes for farm_bench: daemons that run in the background with their output in a log
// file (radfarmd, radfarm-agent), and commands run to completion with their output captured
// (radfarm render, submit, status, fetch). No shell is involved.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace radfarm::bench {

class ChildProcess {
 public:
  // Starts `args` (args[0] is the program path); stdout and stderr append to `log_path`.
  // Throws std::runtime_error when the program cannot be started.
  ChildProcess(const std::vector<std::string>& args, const std::string& log_path);
  // SIGKILLs and reaps the process if it still runs.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running();
  // SIGTERM, then waits up to `grace` before SIGKILL. Returns the exit code (128 + signal).
  int Stop(std::chrono::milliseconds grace = std::chrono::seconds(5));
  const std::string& log_path() const { return log_path_; }

 private:
  bool Reap(bool block);

  pid_t pid_ = -1;
  std::string log_path_;
  std::optional<int> exit_code_;
};

struct CommandOutput {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `args` to completion with stdout and stderr captured (through files in `scratch_dir`).
CommandOutput RunCommand(const std::vector<std::string>& args, const std::string& scratch_dir);

// CPU seconds (user + system) a process has used so far, from /proc/PID/stat; nullopt if gone.
std::optional<double> ProcessCpuSeconds(pid_t pid);

std::string ReadFile(const std::string& path);

}  // namespace radfarm::bench
