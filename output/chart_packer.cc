#include "output/chart_packer.h"

#include <stb_rect_pack.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radfarm {

std::optional<PackedSquare> PackInto(const std::vector<PackSize>& sizes, uint32_t side) {
  if (side == 0 || side > uint32_t(std::numeric_limits<int>::max())) return std::nullopt;
  std::vector<stbrp_rect> rects(sizes.size());
  for (size_t i = 0; i < sizes.size(); ++i) {
    if (sizes[i].width > side || sizes[i].height > side) return std::nullopt;
    rects[i] = {int(i), int(sizes[i].width), int(sizes[i].height), 0, 0, 0};
  }
  std::vector<stbrp_node> nodes(side);
  stbrp_context context;
  stbrp_init_target(&context, int(side), int(side), nodes.data(), int(nodes.size()));
  if (!rects.empty() && stbrp_pack_rects(&context, rects.data(), int(rects.size())) != 1) {
    return std::nullopt;
  }
  PackedSquare out;
  out.side = side;
  out.at.resize(sizes.size());
  for (const stbrp_rect& r : rects) out.at[size_t(r.id)] = {uint32_t(r.x), uint32_t(r.y)};
  return out;
}

std::optional<PackedSquare> PackSmallest(const std::vector<PackSize>& sizes, uint32_t max_side) {
  double area = 0;
  uint32_t widest = 1;
  for (const PackSize& s : sizes) {
    area += double(s.width) * s.height;
    widest = std::max({widest, s.width, s.height});
  }
  const auto round4 = [](double side) { return (uint32_t(std::ceil(side)) + 3) / 4 * 4; };
  for (uint32_t side = round4(std::max(std::sqrt(area), double(widest))); side <= max_side;
       side = round4(side * 1.03 + 1)) {
    std::optional<PackedSquare> packed = PackInto(sizes, side);
    if (packed) return packed;
  }
  return std::nullopt;
}

}  // namespace radfarm
