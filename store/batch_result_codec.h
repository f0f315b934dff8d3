// The blob of one accepted batch result kept while its round runs (round_results, schema version
// 6). Integers only, so it is exact by construction; the same bytes on any host:
//
//   "RFH2"                                                   4 bytes, the format
//   escaped_weight, escaped_rays, back_weight, back_rays,    LEB128 varints
//   hit count
//   per hit: patch id less the previous hit's (the first:    LEB128 varints
//   the id itself), weight
//
// Hits are in increasing patch order and a shot's rays weigh 1 each (sobol, random), so a hit
// takes about 3 bytes instead of the 12 of fixed-width fields (format 1, below): at 10^5-10^6
// patches a round's kept results are most of what the master writes. Format 1, written before,
// still decodes: 5 x uint64 little-endian, then per hit patch (uint32) and weight (uint64).
//
// Decoding checks that every byte is used, and that hits are in increasing patch order with no
// zero weight (core/batch.h), so a blob that decodes is one the fold would accept.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "core/batch.h"

namespace radfarm::store {

std::vector<uint8_t> EncodeBatchResult(const BatchResult& result);
Result<BatchResult> DecodeBatchResult(std::span<const uint8_t> bytes);

// Format 1, for the tests of reading results an older master kept.
std::vector<uint8_t> EncodeBatchResultFormat1(const BatchResult& result);

}  // namespace radfarm::store
