#include "testing/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "testing/temp_dir.h"

extern char** environ;

namespace radfarm::testing {
namespace {

// environ with `changes` applied ("NAME=value" sets, "NAME" removes).
std::vector<std::string> ChangedEnvironment(const std::vector<std::string>& changes) {
  const auto name_of = [](const std::string& entry) { return entry.substr(0, entry.find('=')); };
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    bool changed = false;
    for (const std::string& c : changes) changed = changed || name_of(c) == name_of(*e);
    if (!changed) env.push_back(*e);
  }
  for (const std::string& c : changes) {
    if (c.find('=') != std::string::npos) env.push_back(c);
  }
  return env;
}

// Starts `args` with stdin from /dev/null, stdout appended to `out_path` and stderr to `err_path`
// (the same file when the paths are equal).
pid_t Spawn(const std::vector<std::string>& args, const std::string& out_path,
            const std::string& err_path, const std::vector<std::string>& env_changes) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_APPEND,
                                   0600);
  if (err_path == out_path) {
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
  } else {
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_APPEND,
                                     0600);
  }
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> env = ChangedEnvironment(env_changes);
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + args[0]);
  return pid;
}

int ExitCode(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

CommandResult RunCommand(const std::vector<std::string>& args,
                         const std::vector<std::string>& env_changes) {
  // Output goes to files rather than pipes, so a chatty child can never block on a full pipe
  // while we wait for it.
  const TempDir dir("radfarm-command");
  const std::string out_path = dir.File("stdout"), err_path = dir.File("stderr");
  const pid_t pid = Spawn(args, out_path, err_path, env_changes);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return {ExitCode(status), ReadFile(out_path), ReadFile(err_path)};
}

ChildProcess::ChildProcess(const std::vector<std::string>& args, const std::string& log_path)
    : pid_(Spawn(args, log_path, log_path, {})), log_path_(log_path) {}

ChildProcess::~ChildProcess() { Kill(); }

bool ChildProcess::Reap(bool block) {
  if (exit_code_) return true;
  int status = 0;
  if (waitpid(pid_, &status, block ? 0 : WNOHANG) != pid_) return false;
  exit_code_ = ExitCode(status);
  return true;
}

bool ChildProcess::running() { return !Reap(false); }

void ChildProcess::Signal(int signum) {
  if (running()) ::kill(pid_, signum);
}

std::optional<int> ChildProcess::WaitExit(std::chrono::milliseconds timeout) {
  WaitUntil([&] { return Reap(false); }, timeout, std::chrono::milliseconds(10));
  return exit_code_;
}

int ChildProcess::Stop(std::chrono::milliseconds grace) {
  Signal(SIGTERM);
  if (!WaitExit(grace)) Kill();
  return *exit_code_;
}

void ChildProcess::Kill() {
  if (!running()) return;
  ::kill(pid_, SIGCONT);
  ::kill(pid_, SIGKILL);
  Reap(true);
}

std::string ChildProcess::Log() const { return ReadFile(log_path_); }

bool WaitUntil(const std::function<bool()>& done, std::chrono::milliseconds timeout,
               std::chrono::milliseconds poll) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(poll);
  }
  return true;
}

namespace {

// User + system CPU seconds from a /proc stat file (a process's or one of its threads').
std::optional<double> StatCpuSeconds(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!std::getline(in, text)) return std::nullopt;
  // Fields after the parenthesised command name: state is field 3, utime 14, stime 15.
  const size_t paren = text.rfind(')');
  if (paren == std::string::npos) return std::nullopt;
  std::istringstream fields(text.substr(paren + 2));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int index = 3; fields >> field; ++index) {
    if (index == 14) utime = std::stoull(field);
    if (index == 15) {
      stime = std::stoull(field);
      return double(utime + stime) / double(sysconf(_SC_CLK_TCK));
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> ProcessCpuSeconds(pid_t pid) {
  return StatCpuSeconds("/proc/" + std::to_string(pid) + "/stat");
}

std::optional<double> MainThreadCpuSeconds(pid_t pid) {
  const std::string id = std::to_string(pid);
  return StatCpuSeconds("/proc/" + id + "/task/" + id + "/stat");
}

}  // namespace radfarm::testing
