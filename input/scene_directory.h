// What a scene may read. Every file a scene names (a glTF buffer or image uri, an OBJ's mtllib, an
// MTL's texture maps) must lie, after symlinks, inside the directory tree of the scene file
// itself, outside /proc, /sys and /dev. A scene from someone else then cannot name a file of yours
// (the farm secret, /proc/self/environ) and have its bytes come back in lit.glb, the job store or
// `fetch`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "base/result.h"

namespace radfarm {

class SceneDirectory {
 public:
  // `scene_path`: the scene file as given; its directory, with symlinks resolved, is the root.
  explicit SceneDirectory(const std::string& scene_path);

  // The canonical path of the file `name` names, `name` being relative to `from` (a directory
  // inside the tree; the root when empty), as the scene writes it. The error is the reason alone,
  // for the caller to put after the scene's location and field: "is an absolute path; ...",
  // "leads outside the scene's directory /d (to /etc/passwd); ...", "leads to /proc/self/environ;
  // ...". The file need not exist.
  Result<std::filesystem::path> Resolve(const std::string& name,
                                        const std::filesystem::path& from = {}) const;

  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

}  // namespace radfarm
