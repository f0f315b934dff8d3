// Checksums of what the store keeps (schema version 5), so that rot the file's own checks cannot
// see is noticed: one bit flipped in a checkpoint blob passes `PRAGMA integrity_check`, and the job
// would read `done` and fetch a different solution without a word.
//
//   checkpoints.checksum: BLAKE2b-256 (libsodium crypto_generichash, no key) over, in order, the
//     job id, round, rounds_done and refine_points (each 8 bytes little-endian), then each of the
//     radiosity, unshot and energy blobs, scene_hash and stop_reason as an 8-byte little-endian
//     length and its bytes (a NULL text as length 2^64 - 1 and no bytes).
//   scenes.checksum: BLAKE2b-256 over the geometry blob.
//   round_results.checksum (version 6): BLAKE2b-256 over the job id, round, batch index, shooter,
//     first_ray, ray_count and batch_rays (each 8 bytes little-endian), then the result blob as an
//     8-byte little-endian length and its bytes.
//   displays.checksum (version 9): BLAKE2b-256 over the display blob.
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

struct RoundResultFields {
  int64_t job = 0;
  int64_t round = 0;
  int64_t index = 0;
  int64_t shooter = 0;
  int64_t first_ray = 0;
  int64_t ray_count = 0;
  int64_t batch_rays = 0;  // as stored: the taper in its high 32 bits
  std::span<const uint8_t> result;
};

Checksum CheckpointChecksum(const CheckpointFields& fields);
Checksum RoundResultChecksum(const RoundResultFields& fields);
Checksum BlobChecksum(std::span<const uint8_t> blob);

// Whether `stored` (a checksum column: empty when NULL) matches; a NULL one always does.
bool ChecksumMatches(const std::vector<uint8_t>& stored, const Checksum& computed);

}  // namespace radfarm::store
