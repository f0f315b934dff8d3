#include "testing/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
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

// Opens `path` on descriptor `target` in a forked child (async-signal-safe calls only).
bool OpenAs(int target, const char* path, int flags) {
  const int fd = ::open(path, flags, 0600);
  if (fd < 0) return false;
  if (fd == target) return true;
  const bool ok = ::dup2(fd, target) == target;
  ::close(fd);
  return ok;
}

// Forks a child that moves itself into the cgroup whose `cgroup.procs` is `procs` and then execs
// `argv` with the descriptors Spawn gives it: posix_spawn has no step between fork and exec. The
// child reports a failure's errno through a close-on-exec pipe, which an exec closes empty.
pid_t ForkIntoCgroup(char* const* argv, char* const* envp, const std::string& procs,
                     const std::string& out_path, const std::string& err_path) {
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    char digits[24], text[24];
    int n = 0, length = 0;
    for (long value = ::getpid(); value > 0; value /= 10) digits[n++] = char('0' + value % 10);
    while (n > 0) text[length++] = digits[--n];
    const int fd = ::open(procs.c_str(), O_WRONLY | O_CLOEXEC);
    bool ok = fd >= 0 && ::write(fd, text, length) == length;
    if (fd >= 0) ::close(fd);
    ok = ok && OpenAs(0, "/dev/null", O_RDONLY) &&
         OpenAs(1, out_path.c_str(), O_WRONLY | O_CREAT | O_APPEND) &&
         (err_path == out_path ? ::dup2(1, 2) == 2
                               : OpenAs(2, err_path.c_str(), O_WRONLY | O_CREAT | O_APPEND));
    if (ok) ::execve(argv[0], argv, envp);
    const int error = errno;
    [[maybe_unused]] const ssize_t written = ::write(report[1], &error, sizeof error);
    ::_exit(127);
  }
  ::close(report[1]);
  int error = 0;
  ssize_t got = 0;
  while ((got = ::read(report[0], &error, sizeof error)) < 0 && errno == EINTR) {
  }
  ::close(report[0]);
  if (pid > 0 && got > 0) {
    while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
    return -1;
  }
  return pid;
}

// Starts `args` with stdin from /dev/null, stdout appended to `out_path` and stderr to `err_path`
// (the same file when the paths are equal), in options.cgroup_procs's group when given.
pid_t Spawn(const std::vector<std::string>& args, const std::string& out_path,
            const std::string& err_path, const ChildOptions& options) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> env = ChangedEnvironment(options.env_changes);
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  if (!options.cgroup_procs.empty()) {
    const pid_t pid =
        ForkIntoCgroup(argv.data(), envp.data(), options.cgroup_procs, out_path, err_path);
    if (pid < 0) {
      throw std::runtime_error("cannot start " + args[0] + " in " + options.cgroup_procs);
    }
    return pid;
  }
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
  return RunCommandWith(args, {.env_changes = env_changes});
}

CommandResult RunCommandWith(const std::vector<std::string>& args, const ChildOptions& options) {
  // Output goes to files rather than pipes, so a chatty child can never block on a full pipe
  // while we wait for it.
  const TempDir dir("radfarm-command");
  const std::string out_path = dir.File("stdout"), err_path = dir.File("stderr");
  const pid_t pid = Spawn(args, out_path, err_path, options);
  int status = 0;
  rusage usage{};
  CommandResult result;
  const auto reaped = [&](int flags) {
    pid_t got = -1;
    while ((got = ::wait4(pid, &status, flags, &usage)) < 0 && errno == EINTR) {
    }
    return got == pid;
  };
  // Polled often: a command's end is timed by the caller (office_bench).
  if (options.timeout.count() > 0 &&
      !WaitUntil([&] { return reaped(WNOHANG); }, options.timeout, std::chrono::milliseconds(5))) {
    ::kill(pid, SIGKILL);
    reaped(0);
    result.timed_out = true;
  } else if (options.timeout.count() == 0) {
    reaped(0);
  }
  result.exit_code = ExitCode(status);
  result.out = ReadFile(out_path);
  result.err = ReadFile(err_path);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + t.tv_usec * 1e-6; };
  result.cpu_seconds = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  return result;
}

ChildProcess::ChildProcess(const std::vector<std::string>& args, const std::string& log_path,
                           const ChildOptions& options)
    : pid_(Spawn(args, log_path, log_path, options)), log_path_(log_path) {}

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
