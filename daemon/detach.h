// `radfarmd --detach`: the daemon forks, and the command returns to its caller only once the
// daemon is ready (store open, both listeners bound, listen.addr written), printing the daemon's
// pid on stdout, or with the daemon's exit code when it could not start. A script can then use the
// master at once: `master=$(radfarmd --detach ...)` races with nothing (pg_ctl -w does the same).
//
//   parent:  Detach() -> waits on a pipe -> 'ready' byte: prints the pid, exits 0
//                                        -> end of file: reaps the child, exits with its code
//   child:   Detach() returns -> ... Master::Start ... -> Ready() writes the byte, closes the pipe
//
// Call Detach before any thread is started (fork copies only the calling thread).
#pragma once

#include <optional>

namespace radfarm::daemon {

class Detached {
 public:
  // In the child: the daemon goes on, in a session of its own, with stdin and stdout on
  // /dev/null (stderr, the log, stays). In the parent it does not return: it exits as above.
  // nullopt when fork or pipe fails (the reason is printed).
  static std::optional<Detached> Detach();

  Detached(Detached&& other) noexcept : ready_fd_(other.ready_fd_) { other.ready_fd_ = -1; }
  Detached(const Detached&) = delete;
  Detached& operator=(const Detached&) = delete;
  ~Detached();

  // Tells the waiting parent that the daemon is ready; once.
  void Ready();

 private:
  explicit Detached(int ready_fd) : ready_fd_(ready_fd) {}
  int ready_fd_ = -1;
};

}  // namespace radfarm::daemon
