#include "protocol/scene_packing.h"

#include <zstd.h>

#include <future>
#include <memory>
#include <stdexcept>
#include <string>

#include "protocol/scene_transfer.h"

namespace radfarm::protocol {
namespace {

std::string Str(uint64_t v) { return std::to_string(v); }

}  // namespace

PackedScene PackScene(std::span<const uint8_t> blob) {
  PackedScene packed;
  packed.size = blob.size();
  // Hashing (libsodium's SHA-256) and compressing read the same blob: side by side they take the
  // longer of the two, not their sum. The agents wait.
  std::future<SceneHash> hash = std::async(std::launch::async, [blob] { return HashScene(blob); });
  // Room for the worst case, left uninitialised so that only the pages zstd writes are touched.
  const size_t bound = ZSTD_compressBound(blob.size());
  const std::unique_ptr<uint8_t[]> room(new uint8_t[bound]);
  const size_t written =
      ZSTD_compress(room.get(), bound, blob.data(), blob.size(), kSceneCompressionLevel);
  // Only a bug (or no memory) makes compressing into compressBound's room fail.
  if (ZSTD_isError(written)) {
    throw std::runtime_error(std::string("zstd: cannot compress the scene: ") +
                             ZSTD_getErrorName(written));
  }
  packed.compressed.assign(room.get(), room.get() + written);
  packed.hash = hash.get();
  return packed;
}

Result<std::vector<uint8_t>> UnpackScene(std::span<const uint8_t> compressed,
                                         uint64_t declared_size, uint64_t max_size) {
  if (declared_size == 0 || declared_size > max_size) {
    return Error{"declared size " + Str(declared_size) + " not in 1.." + Str(max_size) + " bytes"};
  }
  const unsigned long long content = ZSTD_getFrameContentSize(compressed.data(), compressed.size());
  if (content == ZSTD_CONTENTSIZE_ERROR) return Error{"not a zstd frame"};
  if (content == ZSTD_CONTENTSIZE_UNKNOWN) return Error{"zstd frame without its content size"};
  if (content != declared_size) {
    return Error{"zstd frame holds " + Str(content) + " bytes, the chunks declared " +
                 Str(declared_size)};
  }
  std::vector<uint8_t> blob(declared_size);
  const size_t written =
      ZSTD_decompress(blob.data(), blob.size(), compressed.data(), compressed.size());
  if (ZSTD_isError(written)) {
    return Error{std::string("cannot decompress: ") + ZSTD_getErrorName(written)};
  }
  if (written != declared_size) {
    return Error{"decompressed " + Str(written) + " bytes, the chunks declared " +
                 Str(declared_size)};
  }
  return blob;
}

}  // namespace radfarm::protocol
