#include "input/scene_directory.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

#include "base/text_file.h"
#include "base/unique_fd.h"

namespace radfarm {
namespace {

constexpr const char* kRule =
    "a scene may read only files in its own directory and below, named relative to it";

// `path` lies under `root` (or is it): root's components are a prefix of path's.
bool IsWithin(const std::filesystem::path& path, const std::filesystem::path& root) {
  auto p = path.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++p) {
    if (r->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *r) return false;
  }
  return true;
}

// Kernel and device files are never scene data: /proc/self/environ passes for a regular file.
bool IsSystemPath(const std::filesystem::path& path) {
  static const std::array<std::filesystem::path, 3> kSystem = {"/proc", "/sys", "/dev"};
  return std::any_of(kSystem.begin(), kSystem.end(),
                     [&](const std::filesystem::path& dir) { return IsWithin(path, dir); });
}

std::filesystem::path CanonicalOrLexical(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::path out = std::filesystem::weakly_canonical(path, ec);
  return ec ? std::filesystem::absolute(path, ec).lexically_normal() : out;
}

}  // namespace

SceneDirectory::SceneDirectory(const std::string& scene_path, FileReach reach) : reach_(reach) {
  std::filesystem::path dir = std::filesystem::path(scene_path).parent_path();
  if (dir.empty()) dir = ".";
  // A directory that cannot be resolved makes every file in it unreadable anyway.
  root_ = CanonicalOrLexical(dir);
}

Result<std::filesystem::path> SceneDirectory::Resolve(const std::string& name,
                                                      const std::filesystem::path& from) const {
  if (name.empty()) return Error{"is empty"};
  const std::filesystem::path written(name);
  if (written.is_absolute() && reach_ == FileReach::kSceneTree) {
    return Error{"is an absolute path; " + std::string(kRule)};
  }
  std::error_code ec;
  const std::filesystem::path target =
      std::filesystem::weakly_canonical((from.empty() ? root_ : from) / written, ec);
  if (ec) return Error{"cannot be resolved: " + ec.message()};
  if (std::string why = Refusal(target); !why.empty()) return Error{"leads " + why};
  return target;
}

std::string SceneDirectory::Refusal(const std::filesystem::path& target) const {
  if (IsSystemPath(target)) {
    return "to " + target.string() + "; files under /proc, /sys and /dev are not scene data";
  }
  if (reach_ == FileReach::kSceneTree && !IsWithin(target, root_)) {
    return "outside the scene's directory " + root_.string() + " (to " + target.string() + "); " +
           kRule;
  }
  return "";
}

Result<std::string> SceneDirectory::Read(const std::filesystem::path& resolved,
                                         uint64_t max_bytes) const {
  const std::string path = resolved.string();
  UniqueFd fd(OpenForReading(path));
  if (!fd.valid()) return Error{path + ": cannot open: " + std::strerror(errno)};
  // Where the open file really is: a component swapped for a symlink since Resolve shows here.
  std::error_code ec;
  const std::filesystem::path opened =
      std::filesystem::read_symlink("/proc/self/fd/" + std::to_string(fd.get()), ec);
  if (ec) return Error{path + ": cannot tell where the opened file lies: " + ec.message()};
  if (std::string why = Refusal(opened); !why.empty()) {
    return Error{path + ": is reached through a symlink that now leads " + why};
  }
  return ReadOpenFile(fd.get(), path, max_bytes);
}

}  // namespace radfarm
