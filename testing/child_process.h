// Child processes for tests and benchmarks, without a shell: commands run to completion with their
// output captured (RunCommand), and daemons that run in the background with their output in a log
// file (ChildProcess: radfarmd, radfarm-agent), which the caller can signal, wait for and read.
// Waits poll a condition (WaitUntil) with a timeout; nothing sleeps a fixed time to synchronise.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace radfarm::testing {

struct CommandResult {
  int exit_code = -1;  // 128 + signal when killed by one
  std::string out;
  std::string err;
  double cpu_seconds = 0;  // user + system, its threads and the children it waited for
  bool timed_out = false;  // killed for outliving ChildOptions::timeout
};

// How a child starts. `env_changes` edit the environment: "NAME=value" sets a variable, "NAME"
// removes it. `cgroup_procs`, when not empty, is a group's `cgroup.procs` (testing/cpu_cap.h) the
// child writes its pid to before it execs. `timeout` (RunCommandWith only; zero: none) bounds a
// command's run: it is SIGKILLed after it.
// Every member has an initializer, so designated initializers may leave any of them out.
struct ChildOptions {
  std::vector<std::string> env_changes = {};
  std::string cgroup_procs = {};
  std::chrono::milliseconds timeout{0};
};

// Runs `args` (args[0] is the program path) and waits for it to finish. `env_changes` edit the
// environment: "NAME=value" sets a variable, "NAME" removes it. Throws std::runtime_error when the
// program cannot be started.
CommandResult RunCommand(const std::vector<std::string>& args,
                         const std::vector<std::string>& env_changes = {});
// RunCommand with every option of ChildOptions.
CommandResult RunCommandWith(const std::vector<std::string>& args, const ChildOptions& options);

// A daemon: started at construction, SIGKILLed and reaped by the destructor, so a failing test or
// benchmark leaves no stray process behind. One thread drives it.
class ChildProcess {
 public:
  // Starts `args` (args[0] is the program path); stdout and stderr append to `log_path`. Throws
  // std::runtime_error when the program cannot be started (or moved into options.cgroup_procs).
  ChildProcess(const std::vector<std::string>& args, const std::string& log_path,
               const ChildOptions& options = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  // Whether it still runs (reaps it if it has exited).
  bool running();
  void Signal(int signum);
  // Waits up to `timeout` for the process to end; its exit code, or nullopt if it still runs.
  std::optional<int> WaitExit(std::chrono::milliseconds timeout);
  // SIGTERM, then SIGKILL if it has not exited after `grace`. Returns the exit code.
  int Stop(std::chrono::milliseconds grace);
  // SIGKILL (after SIGCONT: a stopped process must run to die) and reap.
  void Kill();
  std::string Log() const;
  const std::string& log_path() const { return log_path_; }

 private:
  bool Reap(bool block);

  pid_t pid_ = -1;
  std::string log_path_;
  std::optional<int> exit_code_;
};

// Polls `done` every `poll` until it holds (true) or `timeout` passes (false).
bool WaitUntil(const std::function<bool()>& done,
               std::chrono::milliseconds timeout = std::chrono::seconds(120),
               std::chrono::milliseconds poll = std::chrono::milliseconds(20));

// CPU seconds (user + system) a process has used so far, from /proc/PID/stat; nullopt if gone.
std::optional<double> ProcessCpuSeconds(pid_t pid);
// The same for the process's main thread alone (radfarmd's event loop), /proc/PID/task/PID/stat.
std::optional<double> MainThreadCpuSeconds(pid_t pid);

}  // namespace radfarm::testing
