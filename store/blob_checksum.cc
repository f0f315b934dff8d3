#include "store/blob_checksum.h"

#include <sodium.h>

#include <algorithm>

namespace radfarm::store {
namespace {

class Hasher {
 public:
  Hasher() { crypto_generichash_init(&state_, nullptr, 0, kChecksumBytes); }
  void Integer(uint64_t v) {
    uint8_t bytes[8];
    for (int i = 0; i < 8; ++i) bytes[i] = static_cast<uint8_t>(v >> (8 * i));
    crypto_generichash_update(&state_, bytes, sizeof bytes);
  }
  void Bytes(std::span<const uint8_t> bytes) {
    Integer(bytes.size());
    crypto_generichash_update(&state_, bytes.data(), bytes.size());
  }
  void Text(const std::optional<std::string>* text) {
    if (text == nullptr || !*text) {
      Integer(~uint64_t{0});
      return;
    }
    Bytes(std::span(reinterpret_cast<const uint8_t*>((*text)->data()), (*text)->size()));
  }
  Checksum Final() {
    Checksum out;
    crypto_generichash_final(&state_, out.data(), out.size());
    return out;
  }

 private:
  crypto_generichash_state state_;
};

}  // namespace

Checksum CheckpointChecksum(const CheckpointFields& f) {
  Hasher h;
  for (int64_t v : {f.job, f.round, f.rounds_done, f.refine_points}) h.Integer(uint64_t(v));
  h.Bytes(f.radiosity);
  h.Bytes(f.unshot);
  h.Bytes(f.energy);
  h.Text(f.scene_hash);
  h.Text(f.stop_reason);
  return h.Final();
}

Checksum RoundResultChecksum(const RoundResultFields& f) {
  Hasher h;
  for (int64_t v : {f.job, f.round, f.index, f.shooter, f.first_ray, f.ray_count, f.batch_rays}) {
    h.Integer(uint64_t(v));
  }
  h.Bytes(f.result);
  return h.Final();
}

Checksum BlobChecksum(std::span<const uint8_t> blob) {
  Checksum out;
  crypto_generichash(out.data(), out.size(), blob.data(), blob.size(), nullptr, 0);
  return out;
}

bool ChecksumMatches(const std::vector<uint8_t>& stored, const Checksum& computed) {
  return stored.empty() ||
         std::equal(stored.begin(), stored.end(), computed.begin(), computed.end());
}

}  // namespace radfarm::store
