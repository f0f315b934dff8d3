// The blob of one accepted batch result kept while its round runs (round_results, schema version
// 6). Integers only, so it is exact by construction; little-endian on any host:
//
//   escaped_weight, escaped_rays, back_weight, back_rays, hit count   5 x uint64
//   per hit: patch (uint32), weight (uint64)                          12 bytes each
//
// Decoding checks the size against the hit count and that hits are in increasing patch order
// with no zero weight (core/batch.h), so a blob that decodes is one the fold would accept.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "core/batch.h"

namespace radfarm::store {

inline constexpr size_t kBatchResultHeaderBytes = 40;
inline constexpr size_t kBatchResultHitBytes = 12;

std::vector<uint8_t> EncodeBatchResult(const BatchResult& result);
Result<BatchResult> DecodeBatchResult(std::span<const uint8_t> bytes);

}  // namespace radfarm::store
