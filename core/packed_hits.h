// A batch's hits as bytes, for the wire (protocol version 5's LeaseResult) and the job store (a
// kept round result, store/batch_result_codec.h): per hit, its patch id less the previous hit's
// (the first: the id itself) and its weight, both LEB128 varints (7 bits a byte, low first, the
// top bit set on every byte but the last).
//
// Hits are in increasing patch order and a Sobol or random ray weighs 1, so a hit takes 2-3 bytes
// instead of the 16 of a FlatBuffers struct of a uint32 and a uint64: results are most of a job's
// bytes on the wire, encrypted and decrypted, copied and allocated on both sides.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/batch.h"

namespace radfarm {

void AppendVarint(uint64_t value, std::vector<uint8_t>* out);

// The varint at bytes[*at], *at moved past it; nullopt when the bytes end inside it or it runs
// over 64 bits.
std::optional<uint64_t> ReadVarint(std::span<const uint8_t> bytes, size_t* at);

void AppendPackedHits(std::span<const PatchHits> hits, std::vector<uint8_t>* out);

// How many bytes AppendPackedHits adds for `hits` (the agent sizes its result frames by it).
size_t PackedHitsBytes(std::span<const PatchHits> hits);

// Reads `count` hits from bytes[*at] on into *hits (replacing what it held), *at moved past them.
// Returns an empty string, or what is wrong ("hit 3 ends inside a number", "hit 3 is out of patch
// order or has no weight", a count the bytes cannot hold): a list that reads is one the fold
// accepts. Nothing is allocated for more hits than the bytes can hold.
std::string ReadPackedHits(std::span<const uint8_t> bytes, size_t* at, uint64_t count,
                           std::vector<PatchHits>* hits);

}  // namespace radfarm
