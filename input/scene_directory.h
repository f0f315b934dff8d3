// What a scene may read. Every file a scene names (a glTF buffer or image uri, an OBJ's mtllib, an
// MTL's texture maps) must lie, after symlinks, inside the directory tree of the scene file
// itself, outside /proc, /sys and /dev. A scene from someone else then cannot name a file of yours
// (the farm secret, /proc/self/environ) and have its bytes come back in lit.glb, the job store or
// `fetch`. A user who trusts a scene that names files elsewhere says so (FileReach::kAnywhere:
// render's and submit's --allow-outside-files); /proc, /sys and /dev stay refused.
//
// The check holds for the file read, not only for the name: Read opens the file, then checks the
// path the open file really has, so a directory swapped for a symlink between the check and the
// open cannot lead the read outside.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "base/result.h"

namespace radfarm {

enum class FileReach {
  kSceneTree,  // the scene's directory and below
  kAnywhere,   // any file but those under /proc, /sys and /dev
};

class SceneDirectory {
 public:
  // `scene_path`: the scene file as given; its directory, with symlinks resolved, is the root.
  explicit SceneDirectory(const std::string& scene_path, FileReach reach = FileReach::kSceneTree);

  // The canonical path of the file `name` names, `name` being relative to `from` (a directory
  // inside the tree; the root when empty), as the scene writes it. The error is the reason alone,
  // for the caller to put after the scene's location and field: "is an absolute path; ...",
  // "leads outside the scene's directory /d (to /etc/passwd); ...", "leads to /proc/self/environ;
  // ...". The file need not exist.
  Result<std::filesystem::path> Resolve(const std::string& name,
                                        const std::filesystem::path& from = {}) const;
  // The bytes of `resolved`, a path Resolve gave, read as ReadTextFile reads (regular files of at
  // most `max_bytes`), once the file it opened is found where Resolve allowed: "path: is reached
  // through a symlink that now leads to /elsewhere; ..." otherwise.
  Result<std::string> Read(const std::filesystem::path& resolved, uint64_t max_bytes) const;

  const std::filesystem::path& root() const { return root_; }

 private:
  // Why `target`, a canonical path, may not be read, or empty when it may.
  std::string Refusal(const std::filesystem::path& target) const;

  std::filesystem::path root_;
  FileReach reach_;
};

}  // namespace radfarm
