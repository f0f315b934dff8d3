// A daemon under test: a child process whose stdout and stderr go to a log file, which the test
// can signal (SIGKILL, SIGSTOP, SIGCONT, SIGTERM), wait for with a timeout, and read the log of.
// The destructor kills and reaps it, so a failing test leaves no stray daemon behind.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace radfarm::testing {

class ChildProcess {
 public:
  // Starts `args` (args[0] is the program path); output appends to `log_path`.
  ChildProcess(const std::vector<std::string>& args, const std::string& log_path);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running() const { return !exit_code_.has_value(); }
  void Signal(int signum);
  // Waits up to `timeout` for the process to end; its exit code (128 + signal when killed), or
  // nullopt if it is still running.
  std::optional<int> WaitExit(std::chrono::milliseconds timeout);
  // SIGKILL and reap.
  void Kill();
  std::string Log() const;
  const std::string& log_path() const { return log_path_; }

 private:
  bool Reap(bool block);

  pid_t pid_ = -1;
  std::string log_path_;
  std::optional<int> exit_code_;
};

// Polls `done` (every 20 ms) until it holds or `timeout` passes.
bool WaitUntil(const std::function<bool()>& done,
               std::chrono::milliseconds timeout = std::chrono::seconds(120));

}  // namespace radfarm::testing
