#include "base/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace radfarm {
namespace {

Error Fail(const std::string& path, const char* step, int error_number) {
  return Error{path + ": " + step + ": " + std::strerror(error_number)};
}

constexpr std::string_view kTemporaryMarker = ".tmp.";

// Unique within the process via the counter and across processes via the pid; O_EXCL below makes a
// collision with a stale file an error instead of a silent overwrite.
std::string TemporaryName(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + std::string(kTemporaryMarker) + std::to_string(getpid()) + "." +
         std::to_string(counter++);
}

Status WriteAll(int fd, std::string_view contents) {
  const char* data = contents.data();
  size_t left = contents.size();
  while (left > 0) {
    const ssize_t written = write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      return Error{std::strerror(errno)};
    }
    data += written;
    left -= static_cast<size_t>(written);
  }
  return Ok{};
}

std::string DirectoryOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// Makes the rename itself durable. Best effort: some file systems refuse fsync on directories.
void SyncDirectory(const std::string& path) {
  const int fd = open(DirectoryOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  fsync(fd);
  close(fd);
}

}  // namespace

Status WriteFileAtomically(const std::string& path, std::string_view contents) {
  if (path.empty()) return Error{"(empty path): cannot write a file without a name"};
  const std::string temporary = TemporaryName(path);
  // 0666 lets the umask decide the final permissions, as for any newly created file.
  const int fd = open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) return Fail(path, "cannot create temporary file", errno);

  Status written = WriteAll(fd, contents);
  // fsync before rename: otherwise a crash can leave the new name pointing at an empty file.
  if (written.ok() && fsync(fd) != 0) written = Error{std::strerror(errno)};
  if (close(fd) != 0 && written.ok()) written = Error{std::strerror(errno)};
  if (!written.ok()) {
    unlink(temporary.c_str());
    return Error{path + ": cannot write: " + written.error()};
  }
  if (rename(temporary.c_str(), path.c_str()) != 0) {
    const int rename_errno = errno;
    unlink(temporary.c_str());
    return Fail(path, "cannot rename temporary file into place", rename_errno);
  }
  SyncDirectory(path);
  return Ok{};
}

bool IsAtomicFileTemporary(std::string_view name) {
  const size_t marker = name.rfind(kTemporaryMarker);
  if (marker == std::string_view::npos || marker == 0) return false;
  // ".tmp." then the pid, a dot and the counter: digits and exactly one dot.
  const std::string_view tail = name.substr(marker + kTemporaryMarker.size());
  const size_t dot = tail.find('.');
  if (dot == 0 || dot == std::string_view::npos || dot + 1 == tail.size()) return false;
  for (size_t i = 0; i < tail.size(); ++i) {
    if (i != dot && (tail[i] < '0' || tail[i] > '9')) return false;
  }
  return true;
}

}  // namespace radfarm
