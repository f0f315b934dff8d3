// SceneStore: scene blobs kept on disk between runs, in STATE/scenes/<64 hex digits>.scene, each
// named by its SHA-256 (protocol/scene_transfer.h). A blob is written to a temporary file in the
// same directory, fsynced and renamed into place, so a crash leaves either the whole file or no
// file; every load checks the hash again, so a file damaged on disk is found, deleted and fetched
// anew. Several agents may share a state directory: each writes its own temporary name, and rename
// is atomic.
//
// Threads: the methods are const and touch only the file system; the agent calls them from its
// I/O worker thread.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/result.h"
#include "protocol/messages.h"

namespace radfarm::agent {

class SceneStore {
 public:
  // Creates STATE and STATE/scenes if missing, and removes temporary files a crashed agent left
  // behind. Errors name the directory.
  static Result<SceneStore> Open(const std::string& state_dir);

  enum class LoadOutcome {
    kFound,    // `blob` holds the verified scene
    kMissing,  // no file (or an unreadable one: `detail` says why)
    kCorrupt,  // the file's SHA-256 is not its name: it has been deleted; `detail` says so
  };
  struct Loaded {
    LoadOutcome outcome = LoadOutcome::kMissing;
    std::vector<uint8_t> blob;
    std::string detail;
  };
  Loaded Load(const protocol::SceneHash& hash) const;

  // Writes the blob under its hash (temporary file, fsync, rename, fsync of the directory).
  Status Save(const protocol::SceneHash& hash, std::span<const uint8_t> blob) const;
  // Save's first half: the blob written to a temporary file (its temporary_path(), readable at
  // once); the writer's Commit() later makes it durable and puts it in place, and destroying the
  // writer uncommitted removes it. An agent reads the scene back from the temporary and commits
  // once the scene is ready, so the fsync is not on the way to the first batch.
  Result<AtomicFileWriter> Write(const protocol::SceneHash& hash,
                                 std::span<const uint8_t> blob) const;

  std::string PathFor(const protocol::SceneHash& hash) const;
  const std::string& scenes_dir() const { return scenes_dir_; }

 private:
  explicit SceneStore(std::string scenes_dir) : scenes_dir_(std::move(scenes_dir)) {}
  std::string scenes_dir_;
};

}  // namespace radfarm::agent
