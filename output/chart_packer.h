// Rectangles packed without overlap into a square, by stb_rect_pack (the skyline packer, its
// bottom-left heuristic), for the charts of an unwrapped lightmap (lightmap_unwrap.h).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace radfarm {

struct PackSize {
  uint32_t width = 0;
  uint32_t height = 0;
};

// Each rectangle's top-left corner, by input order, in a square of `side`.
struct PackedSquare {
  uint32_t side = 0;
  std::vector<std::array<uint32_t, 2>> at;
};

// Packs `sizes` into a square of exactly `side`; nullopt when they do not all fit.
std::optional<PackedSquare> PackInto(const std::vector<PackSize>& sizes, uint32_t side);

// The smallest square the packer fits them in, its side a multiple of 4 (searched upward from
// the side of their total area in steps of about 3 %), or nullopt when that exceeds `max_side`.
std::optional<PackedSquare> PackSmallest(const std::vector<PackSize>& sizes, uint32_t max_side);

}  // namespace radfarm
