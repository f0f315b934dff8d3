// Scene distribution by content hash. A scene blob (whatever the master serialises a job's scene
// as; opaque here) is named by its SHA-256. The master serves it compressed (a PackedScene,
// scene_packing.h, made once per scene). An agent that lacks it sends SceneRequests for ranges of
// the compressed bytes and the master answers each with one SceneChunk, in order; once the last
// byte is in, the agent decompresses into the declared size and checks the hash (UnpackReceived,
// off its event loop: about a second for a scene of 10^6 patches), and only then uses the scene.
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

// A fetched scene as it came: compressed, with the size and hash it must unpack to.
struct ReceivedScene {
  SceneHash hash{};
  uint64_t scene_size = 0;  // as the chunks declared it, within max_scene_bytes
  uint64_t max_scene_bytes = 0;
  std::vector<uint8_t> compressed;
};

// Decompresses into the declared size (nothing more) and checks the SHA-256 against the hash the
// scene was asked for: the blob to use, or an error naming the scene. Pure: any thread. Takes the
// scene by value: its compressed bytes (about 30 bytes a patch) are freed once decompressed, and
// never held beside what the caller then builds from the blob.
Result<std::vector<uint8_t>> UnpackReceived(ReceivedScene received);

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
  // time, both within the limit. An error means the fetch failed for good (failed() is then
  // true): start a new SceneAssembler to retry.
  Status Add(const SceneChunkMsg& chunk);

  // Every compressed byte is in (not yet decompressed or checked: UnpackReceived).
  bool complete() const { return complete_; }
  bool failed() const { return failed_; }
  const SceneHash& hash() const { return hash_; }
  // The compressed scene and what it must unpack to, once complete (once only).
  ReceivedScene TakeReceived();
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
  bool complete_ = false;
  bool failed_ = false;
};

}  // namespace radfarm::protocol
