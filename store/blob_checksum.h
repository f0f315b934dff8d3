// Checksums of what the store keeps (schema version 5), so that rot the file's own checks cannot
// see is noticed: one bit flipped in a checkpoint blob passes `PRAGMA integrity_check`, and the job
// would read `done` and fetch a different solution without a word (issue 20, F2).
//
//   checkpoints.checksum: BLAKE2b-256 (libsodium crypto_generichash, no key) over, in order, the
//     job id, round, rounds_done and refine_points (each 8 bytes little-endian), then each of the
//     radiosity, unshot and energy blobs, scene_hash and stop_reason as an 8-byte little-endian
//     length and its bytes (a NULL text as length 2^64 - 1 and no bytes).
//   scenes.checksum: BLAKE2b-256 over the geometry blob.
//
// A row written before version 5 has a NULL checksum: it is read unverified, as before.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace radfarm::store {

inline constexpr size_t kChecksumBytes = 32;
using Checksum = std::array<uint8_t, kChecksumBytes>;

struct CheckpointFields {
  int64_t job = 0;
  int64_t round = 0;
  int64_t rounds_done = 0;
  int64_t refine_points = 0;
  std::span<const uint8_t> radiosity, unshot, energy;
  const std::optional<std::string>* scene_hash = nullptr;
  const std::optional<std::string>* stop_reason = nullptr;
};

Checksum CheckpointChecksum(const CheckpointFields& fields);
Checksum BlobChecksum(std::span<const uint8_t> blob);

// Whether `stored` (a checksum column: empty when NULL) matches; a NULL one always does.
bool ChecksumMatches(const std::vector<uint8_t>& stored, const Checksum& computed);

}  // namespace radfarm::store
