#include "agent/scene_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "base/atomic_file.h"
#include "base/private_dir.h"
#include "base/unique_fd.h"
#include "protocol/limits.h"
#include "protocol/scene_transfer.h"

namespace radfarm::agent {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSuffix = ".scene";
constexpr const char* kOldTempMarker = ".tmp-";

std::string Errno(const std::string& what) { return what + ": " + std::strerror(errno); }

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

// A crashed writer's temporary: WriteFileAtomically's, or one of older agents (".tmp-PID-N").
bool IsTemporary(const std::string& name) {
  return IsAtomicFileTemporary(name) || name.find(kOldTempMarker) != std::string::npos;
}

}  // namespace

Result<SceneStore> SceneStore::Open(const std::string& state_dir) {
  const fs::path scenes = fs::path(state_dir) / "scenes";
  if (Status made = CreatePrivateDirectories(scenes.string()); !made.ok()) {
    return Error{"state directory " + made.error()};
  }
  std::error_code error;
  if (access(scenes.c_str(), R_OK | W_OK | X_OK) != 0) {
    return Error{Errno("state directory " + scenes.string())};
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(scenes, error)) {
    if (IsTemporary(entry.path().filename().string())) {
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
  Result<AtomicFileWriter> written = Write(hash, blob);
  RADFARM_RETURN_IF_ERROR(written);
  return written->Commit();
}

Result<AtomicFileWriter> SceneStore::Write(const protocol::SceneHash& hash,
                                           std::span<const uint8_t> blob) const {
  // Private: scenes are the farm users' data (base/private_dir.h).
  Result<AtomicFileWriter> writer = AtomicFileWriter::Open(PathFor(hash), 0600);
  RADFARM_RETURN_IF_ERROR(writer);
  RADFARM_RETURN_IF_ERROR(
      writer->Append(std::string_view(reinterpret_cast<const char*>(blob.data()), blob.size())));
  RADFARM_RETURN_IF_ERROR(writer->Flush());
  return writer;
}

}  // namespace radfarm::agent
