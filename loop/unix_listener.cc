#include "loop/unix_listener.h"

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "base/result.h"
#include "loop/listen_block.h"
#include "loop/log.h"
#include "loop/uv_error.h"

namespace radfarm::loop {
namespace {

constexpr mode_t kSocketMode = 0600;

std::string Errno(const std::string& what) { return what + ": " + std::strerror(errno); }

// EADDRINUSE at bind: a live daemon, or the file of a dead one. Removes the latter.
Status RemoveStaleSocket(const std::string& path) {
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) return Ok{};  // gone meanwhile: bind again
  if (!S_ISSOCK(st.st_mode))
    return Error{"listen on unix:" + path + ": exists and is not a socket"};
  const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return Error{Errno("listen on unix:" + path + ": socket")};
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::memcpy(address.sun_path, path.data(), path.size());
  const int rc = connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  const int connect_errno = errno;
  close(fd);
  if (rc == 0) {
    return Error{"listen on unix:" + path +
                 ": another process is listening there (is the daemon already running?)"};
  }
  if (connect_errno != ECONNREFUSED) {
    errno = connect_errno;
    return Error{Errno("listen on unix:" + path + ": in use, and probing it failed")};
  }
  if (unlink(path.c_str()) != 0 && errno != ENOENT) {
    return Error{Errno("listen on unix:" + path + ": removing the stale socket")};
  }
  Log(LogLevel::kInfo, "loop", "removed stale socket " + path);
  return Ok{};
}

}  // namespace

Result<std::unique_ptr<UnixListener>> UnixListener::Listen(EventLoop& loop, const std::string& path,
                                                           OnConnection on_connection) {
  internal::CheckLoopThread(loop.uv());
  if (path.empty() || path.size() >= sizeof(sockaddr_un{}.sun_path)) {
    return Error{"listen on unix:" + path + ": the path must be 1 to " +
                 std::to_string(sizeof(sockaddr_un{}.sun_path) - 1) + " bytes"};
  }
  std::unique_ptr<UnixListener> listener(new UnixListener);
  listener->path_ = path;
  auto* block = new internal::ListenBlock(loop.uv(), /*unix=*/true, std::move(on_connection));
  listener->block_.Reset(block);
  block->name = path;
  int rc = uv_pipe_bind(&block->pipe, path.c_str());
  if (rc == UV_EADDRINUSE) {
    RADFARM_RETURN_IF_ERROR(RemoveStaleSocket(path));
    rc = uv_pipe_bind(&block->pipe, path.c_str());
  }
  if (rc < 0) return UvError("listen on unix:" + path, rc);

  // From here the file is ours: closing the listener (also on the error paths below, when the
  // wrapper is destroyed) unlinks it, unless someone replaced it.
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) return Error{Errno("listen on unix:" + path + ": stat")};
  const dev_t device = st.st_dev;
  const ino_t inode = st.st_ino;
  block->on_closing = [path, device, inode] {
    struct stat now {};
    if (lstat(path.c_str(), &now) == 0 && now.st_dev == device && now.st_ino == inode) {
      unlink(path.c_str());
    }
  };

  // Before listen(): see the header.
  if (chmod(path.c_str(), kSocketMode) != 0) {
    return Error{Errno("listen on unix:" + path + ": chmod 0600")};
  }
  if (lstat(path.c_str(), &st) != 0 || !S_ISSOCK(st.st_mode) || st.st_uid != geteuid() ||
      (st.st_mode & 07777) != kSocketMode || st.st_ino != inode || st.st_dev != device) {
    return Error{"listen on unix:" + path +
                 ": the socket file changed under us (is its directory writable by others?)"};
  }
  RADFARM_RETURN_IF_ERROR(block->Listen());
  return listener;
}

void UnixListener::Close() {
  if (block_.open()) block_->BeginClose();
}

HandleState UnixListener::state() const { return block_.state(); }

}  // namespace radfarm::loop
