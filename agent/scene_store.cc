#include "agent/scene_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>

#include "base/unique_fd.h"
#include "protocol/limits.h"
#include "protocol/scene_transfer.h"

namespace radfarm::agent {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSuffix = ".scene";
constexpr const char* kTempMarker = ".tmp-";

std::string Errno(const std::string& what) { return what + ": " + std::strerror(errno); }

Status WriteAll(int fd, std::span<const uint8_t> bytes, const std::string& path) {
  while (!bytes.empty()) {
    const ssize_t n = write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return Error{Errno("write " + path)};
    bytes = bytes.subspan(static_cast<size_t>(n));
  }
  return Ok{};
}

Result<std::vector<uint8_t>> ReadAll(int fd, const std::string& path) {
  struct stat info {};
  if (fstat(fd, &info) != 0) return Error{Errno("stat " + path)};
  if (static_cast<uint64_t>(info.st_size) > protocol::kDefaultMaxSceneBytes) {
    return Error{path + ": " + std::to_string(info.st_size) + " bytes, larger than any scene"};
  }
  std::vector<uint8_t> blob(static_cast<size_t>(info.st_size));
  size_t done = 0;
  while (done < blob.size()) {
    const ssize_t n = read(fd, blob.data() + done, blob.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return Error{Errno("read " + path)};
    if (n == 0) break;  // shrank under us: the hash check will say so
    done += static_cast<size_t>(n);
  }
  blob.resize(done);
  return blob;
}

std::string TempSuffix() {
  std::random_device random;
  return std::string(kTempMarker) + std::to_string(getpid()) + "-" + std::to_string(random());
}

}  // namespace

Result<SceneStore> SceneStore::Open(const std::string& state_dir) {
  const fs::path scenes = fs::path(state_dir) / "scenes";
  std::error_code error;
  fs::create_directories(scenes, error);
  if (error) return Error{"state directory " + scenes.string() + ": " + error.message()};
  if (access(scenes.c_str(), R_OK | W_OK | X_OK) != 0) {
    return Error{Errno("state directory " + scenes.string())};
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(scenes, error)) {
    if (entry.path().filename().string().find(kTempMarker) != std::string::npos) {
      fs::remove(entry.path(), error);  // a crashed writer's; a live one would still be renaming
    }
  }
  return SceneStore(scenes.string());
}

std::string SceneStore::PathFor(const protocol::SceneHash& hash) const {
  return scenes_dir_ + "/" + protocol::HashToHex(hash) + kSuffix;
}

SceneStore::Loaded SceneStore::Load(const protocol::SceneHash& hash) const {
  const std::string path = PathFor(hash);
  Loaded loaded;
  UniqueFd fd(open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd.valid()) {
    if (errno != ENOENT) loaded.detail = Errno("open " + path);
    return loaded;
  }
  Result<std::vector<uint8_t>> blob = ReadAll(fd.get(), path);
  if (!blob) {
    loaded.detail = blob.error();
    return loaded;
  }
  if (protocol::HashScene(*blob) != hash) {
    loaded.outcome = LoadOutcome::kCorrupt;
    loaded.detail = path + ": its SHA-256 is not its name (damaged file)";
    if (unlink(path.c_str()) != 0 && errno != ENOENT) {
      loaded.detail += "; " + Errno("cannot delete it");
    } else {
      loaded.detail += "; deleted";
    }
    return loaded;
  }
  loaded.outcome = LoadOutcome::kFound;
  loaded.blob = std::move(blob).value();
  return loaded;
}

Status SceneStore::Save(const protocol::SceneHash& hash, std::span<const uint8_t> blob) const {
  const std::string path = PathFor(hash);
  const std::string temp = path + TempSuffix();
  UniqueFd fd(open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
  if (!fd.valid()) return Error{Errno("create " + temp)};
  Status written = WriteAll(fd.get(), blob, temp);
  if (written && fsync(fd.get()) != 0) written = Error{Errno("fsync " + temp)};
  if (written && fd.Close() != 0) written = Error{Errno("close " + temp)};
  if (written && rename(temp.c_str(), path.c_str()) != 0) {
    written = Error{Errno("rename " + temp + " to " + path)};
  }
  if (!written) {
    unlink(temp.c_str());
    return written;
  }
  // The rename is durable once the directory is synced.
  UniqueFd dir(open(scenes_dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dir.valid()) fsync(dir.get());
  return Ok{};
}

}  // namespace radfarm::agent
