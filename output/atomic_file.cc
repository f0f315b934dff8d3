#include "output/atomic_file.h"

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

// Unique within the process via the counter and across processes via the pid; O_EXCL below makes a
// collision with a stale file an error instead of a silent overwrite.
std::string TemporaryName(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + ".tmp." + std::to_string(getpid()) + "." + std::to_string(counter++);
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

}  // namespace radfarm
