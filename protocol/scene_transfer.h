// Scene distribution by content hash. A scene blob (whatever the master serialises a job's scene
// as; opaque here) is named by its SHA-256. The master serves it compressed (a PackedScene,
// scene_packing.h, made once per scene). An agent that lacks it sends SceneRequests for ranges of
// the compressed bytes and the master answers each with one SceneChunk, in order; once the last
// byte is in, the agent decompresses into the declared size and checks the hash, and only then
// uses the scene.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "protocol/limits.h"
#include "protocol/messages.h"
#include "protocol/scene_packing.h"

namespace radfarm::protocol {

SceneHash HashScene(std::span<const uint8_t> blob);  // SHA-256 (libsodium)
std::string HashToHex(const SceneHash& hash);        // 64 lower-case hex digits
Result<SceneHash> HashFromHex(std::string_view hex);

// Master: the chunk answering `request`, cut from `scene`'s compressed bytes (the scene stored
// under request's hash). Fails for an offset at or past the end.
Result<SceneChunkMsg> MakeSceneChunk(const PackedScene& scene, const SceneRequestMsg& request);

// Agent: one scene being fetched. Requests may be pipelined (NextRequest() again before the chunk
// arrives); chunks must then arrive in request order, as one master connection sends them.
class SceneAssembler {
 public:
  explicit SceneAssembler(const SceneHash& hash, uint64_t max_scene_bytes = kDefaultMaxSceneBytes,
                          uint32_t chunk_bytes = kMaxSceneChunkBytes);

  // The next request to send, or nullopt when every byte has been asked for (or, before the
  // first chunk tells the size, when the first request is out).
  std::optional<SceneRequestMsg> NextRequest();

  // Takes the next chunk: same hash, the expected offset, the same total and scene sizes every
  // time, both within the limit. After the last byte, decompresses (into the declared scene size,
  // nothing more) and checks the SHA-256. An error means the fetch failed for good (failed() is
  // then true): start a new SceneAssembler to retry.
  Status Add(const SceneChunkMsg& chunk);

  bool complete() const { return complete_; }
  bool failed() const { return failed_; }
  const SceneHash& hash() const { return hash_; }
  // The verified, decompressed blob, once complete.
  std::vector<uint8_t> TakeBlob() { return std::move(blob_); }
  // Compressed bytes received (the whole compressed scene once complete).
  uint64_t received_bytes() const { return received_; }

 private:
  Status Fail(std::string reason);

  SceneHash hash_;
  uint64_t max_scene_bytes_;
  uint32_t chunk_bytes_;
  std::optional<uint64_t> total_size_;  // compressed
  uint64_t scene_size_ = 0;             // declared by the first chunk
  uint64_t requested_ = 0;              // bytes asked for so far
  uint64_t received_ = 0;
  std::vector<uint8_t> compressed_;  // reserved to total_size_ at the first chunk
  std::vector<uint8_t> blob_;        // decompressed, once complete
  bool complete_ = false;
  bool failed_ = false;
};

}  // namespace radfarm::protocol
