#include "base/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

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

// Bytes an AtomicFileWriter collects before each write(2).
constexpr size_t kWriteBufferBytes = size_t{1} << 20;

Status WriteFileAtomically(const std::string& path, std::string_view contents) {
  Result<AtomicFileWriter> writer = AtomicFileWriter::Open(path);
  RADFARM_RETURN_IF_ERROR(writer);
  RADFARM_RETURN_IF_ERROR(writer->Append(contents));
  return writer->Commit();
}

Result<AtomicFileWriter> AtomicFileWriter::Open(const std::string& path, unsigned mode) {
  if (path.empty()) return Error{"(empty path): cannot write a file without a name"};
  std::string temporary = TemporaryName(path);
  // The default 0666 lets the umask decide the final permissions, as for any newly created file.
  UniqueFd fd(open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode_t(mode)));
  if (!fd.valid()) return Fail(path, "cannot create temporary file", errno);
  return AtomicFileWriter(path, std::move(temporary), std::move(fd));
}

AtomicFileWriter::AtomicFileWriter(std::string path, std::string temporary, UniqueFd fd)
    : path_(std::move(path)), temporary_(std::move(temporary)), fd_(std::move(fd)) {}

AtomicFileWriter::AtomicFileWriter(AtomicFileWriter&& other) noexcept
    : path_(std::move(other.path_)),
      temporary_(std::exchange(other.temporary_, std::string())),
      fd_(std::move(other.fd_)),
      buffer_(std::move(other.buffer_)),
      error_(std::move(other.error_)) {}

AtomicFileWriter::~AtomicFileWriter() {
  if (temporary_.empty()) return;  // committed, or moved from
  fd_.Reset();
  unlink(temporary_.c_str());
}

Status AtomicFileWriter::Flush() {
  if (!error_.empty()) return Error{error_};
  if (Status written = WriteAll(fd_.get(), buffer_); !written.ok()) {
    error_ = path_ + ": cannot write: " + written.error();
    return Error{error_};
  }
  buffer_.clear();
  return Ok{};
}

Status AtomicFileWriter::Append(std::string_view bytes) {
  if (!error_.empty()) return Error{error_};
  if (temporary_.empty()) return Error{path_ + ": cannot write: the file is already committed"};
  if (buffer_.size() + bytes.size() > kWriteBufferBytes) {
    RADFARM_RETURN_IF_ERROR(Flush());
    if (bytes.size() >= kWriteBufferBytes) {  // large pieces go straight out
      if (Status written = WriteAll(fd_.get(), bytes); !written.ok()) {
        error_ = path_ + ": cannot write: " + written.error();
        return Error{error_};
      }
      return Ok{};
    }
  }
  buffer_.append(bytes);
  return Ok{};
}

Status AtomicFileWriter::Commit() {
  if (temporary_.empty()) return Error{path_ + ": cannot write: the file is already committed"};
  RADFARM_RETURN_IF_ERROR(Flush());
  // fsync before rename: otherwise a crash can leave the new name pointing at an empty file.
  if (fsync(fd_.get()) != 0) error_ = path_ + ": cannot write: " + std::strerror(errno);
  if (fd_.Close() != 0 && error_.empty())
    error_ = path_ + ": cannot write: " + std::strerror(errno);
  if (!error_.empty()) return Error{error_};  // the destructor removes the temporary
  if (rename(temporary_.c_str(), path_.c_str()) != 0) {
    return Fail(path_, "cannot rename temporary file into place", errno);
  }
  temporary_.clear();
  SyncDirectory(path_);
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
