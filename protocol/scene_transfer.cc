#include "protocol/scene_transfer.h"

#include <sodium.h>

#include <algorithm>

#include "base/result.h"
#include "protocol/message_checks.h"

namespace radfarm::protocol {
namespace {

std::string Str(uint64_t v) { return std::to_string(v); }

}  // namespace

SceneHash HashScene(std::span<const uint8_t> blob) {
  static_assert(crypto_hash_sha256_BYTES == kSceneHashBytes);
  SceneHash hash;
  crypto_hash_sha256(hash.data(), blob.data(), blob.size());
  return hash;
}

std::string HashToHex(const SceneHash& hash) {
  std::string hex(2 * hash.size() + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), hash.data(), hash.size());
  hex.pop_back();
  return hex;
}

Result<SceneHash> HashFromHex(std::string_view hex) {
  SceneHash hash;
  size_t decoded = 0;
  const char* end = nullptr;
  if (hex.size() != 2 * hash.size() ||
      sodium_hex2bin(hash.data(), hash.size(), hex.data(), hex.size(), nullptr, &decoded, &end) !=
          0 ||
      decoded != hash.size()) {
    return Error{"scene hash: need 64 hex digits, got '" + std::string(hex.substr(0, 80)) + "'"};
  }
  return hash;
}

Result<SceneChunkMsg> MakeSceneChunk(const PackedScene& scene, const SceneRequestMsg& request) {
  RADFARM_RETURN_IF_ERROR(CheckMessage(request));
  const std::span<const uint8_t> blob = scene.compressed;
  if (request.offset >= blob.size()) {
    return Error{"SceneRequest: offset " + Str(request.offset) + " at or past the scene's " +
                 Str(blob.size()) + " bytes"};
  }
  const size_t length = std::min<uint64_t>(request.max_length, blob.size() - request.offset);
  const auto first = blob.begin() + static_cast<std::ptrdiff_t>(request.offset);
  return SceneChunkMsg{request.scene_hash, blob.size(), request.offset,
                       std::vector<uint8_t>(first, first + static_cast<std::ptrdiff_t>(length)),
                       scene.size};
}

SceneAssembler::SceneAssembler(const SceneHash& hash, uint64_t max_scene_bytes,
                               uint32_t chunk_bytes)
    : hash_(hash),
      max_scene_bytes_(max_scene_bytes),
      chunk_bytes_(std::clamp<uint32_t>(chunk_bytes, 1, kMaxSceneChunkBytes)) {}

std::optional<SceneRequestMsg> SceneAssembler::NextRequest() {
  if (complete_ || failed_) return std::nullopt;
  if (!total_size_ ? requested_ > 0 : requested_ >= *total_size_) return std::nullopt;
  SceneRequestMsg request{hash_, requested_, chunk_bytes_};
  if (total_size_) {
    request.max_length =
        static_cast<uint32_t>(std::min<uint64_t>(chunk_bytes_, *total_size_ - requested_));
  }
  requested_ += request.max_length;
  return request;
}

Status SceneAssembler::Add(const SceneChunkMsg& chunk) {
  const std::string where = "scene " + HashToHex(hash_).substr(0, 16) + ": ";
  if (failed_) return Error{where + "fetch already failed"};
  if (complete_) return Fail(where + "chunk after the scene was complete");
  if (Status ok = CheckMessage(chunk); !ok) return Fail(where + ok.error());
  if (chunk.scene_hash != hash_) return Fail(where + "chunk of another scene");
  if (chunk.total_size > max_scene_bytes_ || chunk.scene_size > max_scene_bytes_) {
    return Fail(where + "size " + Str(chunk.scene_size) + " (" + Str(chunk.total_size) +
                " compressed) exceeds the limit of " + Str(max_scene_bytes_) + " bytes");
  }
  if (total_size_ && (chunk.total_size != *total_size_ || chunk.scene_size != scene_size_)) {
    return Fail(where + "size changed from " + Str(scene_size_) + " (" + Str(*total_size_) +
                " compressed) to " + Str(chunk.scene_size) + " (" + Str(chunk.total_size) + ")");
  }
  if (chunk.offset != received_) {
    return Fail(where + "chunk at offset " + Str(chunk.offset) + ", expected " + Str(received_));
  }
  if (!total_size_) compressed_.reserve(chunk.total_size);  // within the limit: checked above
  total_size_ = chunk.total_size;
  scene_size_ = chunk.scene_size;
  received_ += chunk.data.size();
  // The first request was sent before the size was known; never ask past the end.
  requested_ = std::min(std::max(requested_, received_), *total_size_);
  compressed_.insert(compressed_.end(), chunk.data.begin(), chunk.data.end());
  complete_ = received_ >= *total_size_;
  return Ok{};
}

ReceivedScene SceneAssembler::TakeReceived() {
  ReceivedScene received;
  if (!complete_) return received;
  received.hash = hash_;
  received.scene_size = scene_size_;
  received.max_scene_bytes = max_scene_bytes_;
  received.compressed = std::move(compressed_);
  compressed_.clear();
  return received;
}

Result<std::vector<uint8_t>> UnpackReceived(ReceivedScene received) {
  const std::string where = "scene " + HashToHex(received.hash).substr(0, 16) + ": ";
  Result<std::vector<uint8_t>> blob =
      UnpackScene(received.compressed, received.scene_size, received.max_scene_bytes);
  std::vector<uint8_t>().swap(received.compressed);
  if (!blob) return Error{where + blob.error()};
  if (HashScene(*blob) != received.hash) {
    return Error{where + "SHA-256 of the decompressed bytes does not match"};
  }
  return blob;
}

Status SceneAssembler::Fail(std::string reason) {
  failed_ = true;
  compressed_.clear();
  compressed_.shrink_to_fit();
  return Error{std::move(reason)};
}

}  // namespace radfarm::protocol
