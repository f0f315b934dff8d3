#include "mesh/border_extrapolation.h"

#include <algorithm>
#include <unordered_map>
#include <utility>

namespace radfarm {

void ExtrapolateBorders(const std::vector<std::vector<uint32_t>>& rings, std::vector<Rgb>* values) {
  // Undirected ring edges and how many faces use each.
  std::unordered_map<uint64_t, uint32_t> uses;
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (const std::vector<uint32_t>& ring : rings) {
    for (size_t j = 0; j < ring.size(); ++j) {
      const uint32_t a = std::min(ring[j], ring[(j + 1) % ring.size()]);
      const uint32_t b = std::max(ring[j], ring[(j + 1) % ring.size()]);
      if (uses[(uint64_t{a} << 32) | b]++ == 0) edges.push_back({a, b});
    }
  }
  const size_t n = values->size();
  std::vector<bool> border(n, false);
  for (const auto& [a, b] : edges) {
    if (uses[(uint64_t{a} << 32) | b] == 1) border[a] = border[b] = true;
  }
  std::vector<Rgb> inside_sum(n);
  std::vector<uint32_t> inside_count(n, 0);
  for (const auto& [a, b] : edges) {
    if (border[a] && !border[b]) {
      inside_sum[a] += (*values)[b];
      ++inside_count[a];
    } else if (border[b] && !border[a]) {
      inside_sum[b] += (*values)[a];
      ++inside_count[b];
    }
  }
  for (size_t v = 0; v < n; ++v) {
    if (!border[v] || inside_count[v] == 0) continue;
    const Rgb b = (*values)[v] * 2.0 - inside_sum[v] / double(inside_count[v]);
    (*values)[v] = {std::max(0.0, b.r), std::max(0.0, b.g), std::max(0.0, b.b)};
  }
}

}  // namespace radfarm
