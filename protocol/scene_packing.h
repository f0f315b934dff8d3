// Scene blobs on the wire are zstd-compressed (protocol version 3). The master compresses a job's
// scene once, when it prepares the job (or a refinement step makes a new mesh), and keeps only the
// compressed bytes; every agent's SceneRequests are cut from them. The scene keeps its name: the
// SHA-256 of the uncompressed blob, so stores, checkpoints and agents' caches are unchanged.
//
// An agent decompresses only into a buffer of the size the chunks declare (SceneChunk.scene_size),
// after checking that size against its own limit and against the frame's header: a small frame
// that expands to gigabytes is refused before anything is allocated.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

// zstd level 3 (zstd's default): fast on one core, and it shrinks the FlatBuffer several times.
inline constexpr int kSceneCompressionLevel = 3;

struct PackedScene {
  SceneHash hash{};                 // SHA-256 of the uncompressed blob
  uint64_t size = 0;                // bytes of the uncompressed blob
  std::vector<uint8_t> compressed;  // one zstd frame, with the content size in its header
};

// Hashes and compresses `blob` (deterministic: same blob, same bytes).
PackedScene PackScene(std::span<const uint8_t> blob);

// Decompresses one zstd frame that must expand to exactly `declared_size` bytes, at most
// `max_size`. Allocates only after both checks; errors say which failed.
Result<std::vector<uint8_t>> UnpackScene(std::span<const uint8_t> compressed,
                                         uint64_t declared_size, uint64_t max_size);

}  // namespace radfarm::protocol
