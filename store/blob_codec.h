// Checkpoint blob formats. They are bit-exact: decoding an encoding gives back the same bits
// (including -0.0, denormals and 1e308), on any host byte order.
//
//   radiosity / unshot blob: patches x 24 bytes; patch i at offset 24*i holds r, g, b, each an
//                            IEEE-754 binary64 in little-endian byte order. No header: the patch
//                            count is size / 24 (also stored in checkpoints.patches).
//   energy blob:             32 bytes: emitted, absorbed, escaped, unshot (binary64,
//   little-endian).
//
// Doubles go in blobs rather than REAL columns because SQLite stores integral REALs as integers
// on disk, which turns -0.0 into 0.0.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "core/progressive_solver.h"
#include "core/rgb.h"

namespace radfarm::store {

inline constexpr size_t kRgbBlobBytes = 24;
inline constexpr size_t kEnergyBlobBytes = 32;

std::vector<uint8_t> EncodeRgbs(std::span<const Rgb> values);
// The blob of `values` without a copy where the host's bytes are the blob's (little-endian): a
// view of `values`; elsewhere encoded into `*buffer` and a view of it. Valid while both live.
std::span<const uint8_t> RgbBlob(std::span<const Rgb> values, std::vector<uint8_t>* buffer);
// Errors when the size is not a multiple of 24 bytes.
Result<std::vector<Rgb>> DecodeRgbs(std::span<const uint8_t> bytes);

std::vector<uint8_t> EncodeEnergy(const EnergyAccount& energy);
Result<EnergyAccount> DecodeEnergy(std::span<const uint8_t> bytes);

}  // namespace radfarm::store
