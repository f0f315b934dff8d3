#include "core/packed_hits.h"

#include <algorithm>
#include <bit>

namespace radfarm {

void AppendVarint(uint64_t value, std::vector<uint8_t>* out) {
  while (value >= 0x80) {
    out->push_back(static_cast<uint8_t>(value) | 0x80);
    value >>= 7;
  }
  out->push_back(static_cast<uint8_t>(value));
}

std::optional<uint64_t> ReadVarint(std::span<const uint8_t> bytes, size_t* at) {
  uint64_t value = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (*at >= bytes.size()) return std::nullopt;
    const uint8_t byte = bytes[(*at)++];
    const uint64_t bits = byte & 0x7f;
    if (shift == 63 && bits > 1) return std::nullopt;
    value |= bits << shift;
    if ((byte & 0x80) == 0) return value;
  }
  return std::nullopt;
}

void AppendPackedHits(std::span<const PatchHits> hits, std::vector<uint8_t>* out) {
  uint32_t previous = 0;
  for (const PatchHits& hit : hits) {
    AppendVarint(static_cast<uint32_t>(hit.patch - previous), out);  // modulo 2^32, as read
    AppendVarint(hit.weight, out);
    previous = hit.patch;
  }
}

size_t PackedHitsBytes(std::span<const PatchHits> hits) {
  // A varint of v takes one byte per 7 bits of v's width (at least one).
  const auto bytes_of = [](uint64_t v) { return size_t(1) + (std::bit_width(v | 1) - 1) / 7; };
  size_t total = 0;
  uint32_t previous = 0;
  for (const PatchHits& hit : hits) {
    total += bytes_of(static_cast<uint32_t>(hit.patch - previous)) + bytes_of(hit.weight);
    previous = hit.patch;
  }
  return total;
}

std::string ReadPackedHits(std::span<const uint8_t> bytes, size_t* at, uint64_t count,
                           std::vector<PatchHits>* hits) {
  hits->clear();
  // Each hit takes at least two bytes: a count beyond that is a lie, refused before allocating.
  if (*at > bytes.size() || count > (bytes.size() - *at) / 2) {
    return std::to_string(bytes.size() - std::min(*at, bytes.size())) + " bytes cannot hold " +
           std::to_string(count) + " hits";
  }
  hits->resize(count);
  uint32_t previous = 0;
  for (size_t k = 0; k < count; ++k) {
    const std::optional<uint64_t> delta = ReadVarint(bytes, at);
    const std::optional<uint64_t> weight = delta ? ReadVarint(bytes, at) : std::nullopt;
    if (!weight) return "hit " + std::to_string(k) + " ends inside a number";
    PatchHits& hit = (*hits)[k];
    hit.patch = previous + static_cast<uint32_t>(*delta);  // modulo 2^32: out of order is caught
    hit.weight = *weight;
    if (*delta > UINT32_MAX || hit.weight == 0 || (k > 0 && hit.patch <= previous)) {
      return "hit " + std::to_string(k) + " is out of patch order or has no weight";
    }
    previous = hit.patch;
  }
  return {};
}

}  // namespace radfarm
