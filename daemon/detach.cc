#include "daemon/detach.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace radfarm::daemon {
namespace {

constexpr char kReady = 'R';

// The parent's side: the child's pid on stdout once it is ready, else its exit code.
[[noreturn]] void WaitForReady(pid_t child, int read_fd) {
  char byte = 0;
  ssize_t n;
  do {
    n = ::read(read_fd, &byte, 1);
  } while (n < 0 && errno == EINTR);
  if (n == 1 && byte == kReady) {
    std::printf("%d\n", static_cast<int>(child));
    std::exit(std::fflush(stdout) == 0 ? 0 : 1);
  }
  // End of file: the child ended (or closed the pipe) before it was ready.
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::fprintf(stderr, "radfarmd: the daemon ended before it was ready (exit code %d)\n", code);
  std::exit(code == 0 ? 1 : code);
}

void ToDevNull(int fd) {
  const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
  if (null < 0) return;
  ::dup2(null, fd);
  ::close(null);
}

}  // namespace

std::optional<Detached> Detached::Detach() {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    std::fprintf(stderr, "radfarmd: --detach: pipe: %s\n", std::strerror(errno));
    return std::nullopt;
  }
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) {
    std::fprintf(stderr, "radfarmd: --detach: fork: %s\n", std::strerror(errno));
    ::close(fds[0]);
    ::close(fds[1]);
    return std::nullopt;
  }
  if (child > 0) {
    ::close(fds[1]);
    WaitForReady(child, fds[0]);
  }
  ::close(fds[0]);
  ::setsid();  // no terminal: closing the caller's terminal does not hang the daemon up
  ToDevNull(STDIN_FILENO);
  ToDevNull(STDOUT_FILENO);  // `$(radfarmd --detach ...)` returns when the parent is done
  return Detached(fds[1]);
}

Detached::~Detached() {
  if (ready_fd_ >= 0) ::close(ready_fd_);
}

void Detached::Ready() {
  if (ready_fd_ < 0) return;
  ssize_t n;
  do {
    n = ::write(ready_fd_, &kReady, 1);
  } while (n < 0 && errno == EINTR);
  ::close(ready_fd_);
  ready_fd_ = -1;
}

}  // namespace radfarm::daemon
