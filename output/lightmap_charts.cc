#include "output/lightmap_charts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

namespace radfarm {
namespace {

constexpr double kParallel = 1 - 1e-9;    // cos between unit normals of one plane
constexpr double kPlaneTolerance = 1e-6;  // off the plane, of the object's diagonal

using Key = std::tuple<double, double, double>;

// Neighbours across each triangle's edges: -1 on a border or an edge more than two triangles share.
std::vector<std::array<int64_t, 3>> Neighbours(const std::vector<std::array<Vec3, 3>>& triangles) {
  std::map<Key, uint32_t> ids;
  const auto id = [&ids](const Vec3& p) {
    return ids.try_emplace(Key{p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
  };
  std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, int>>> edges;
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = id(triangles[t][k]), b = id(triangles[t][(k + 1) % 3]);
      if (a != b) edges[std::minmax(a, b)].push_back({t, k});
    }
  }
  std::vector<std::array<int64_t, 3>> out(triangles.size(), {-1, -1, -1});
  for (const auto& [edge, sides] : edges) {
    if (sides.size() != 2) continue;
    out[sides[0].first][sides[0].second] = sides[1].first;
    out[sides[1].first][sides[1].second] = sides[0].first;
  }
  return out;
}

}  // namespace

LightmapCharts MakeLightmapCharts(const std::vector<std::array<Vec3, 3>>& triangles) {
  LightmapCharts out;
  const size_t n = triangles.size();
  out.chart.assign(n, ~0u);
  out.flat.assign(n, {});
  Bounds3 bounds;
  std::vector<Vec3> normal(n);
  std::vector<bool> degenerate(n);
  for (size_t t = 0; t < n; ++t) {
    for (const Vec3& p : triangles[t]) bounds.Extend(p);
    const Vec3 c = Cross(triangles[t][1] - triangles[t][0], triangles[t][2] - triangles[t][0]);
    const double length = Length(c);
    degenerate[t] = !(length > 0) || !std::isfinite(length);
    normal[t] = degenerate[t] ? Vec3{0, 0, 1} : c / length;
  }
  const double tol = kPlaneTolerance * (n > 0 ? bounds.Diagonal() : 1);
  const std::vector<std::array<int64_t, 3>> next = Neighbours(triangles);
  std::vector<uint32_t> stack;
  for (uint32_t seed = 0; seed < n; ++seed) {
    if (out.chart[seed] != ~0u) continue;
    const uint32_t chart = out.count++;
    // The seed's plane and an orthonormal basis of it: u along its first non-zero edge.
    const Vec3 origin = triangles[seed][0], n0 = normal[seed];
    Vec3 u, v;
    const Vec3 edge = triangles[seed][1] - triangles[seed][0];
    if (!degenerate[seed] && Length(edge) > 0) {
      u = Normalize(edge);
      v = Cross(n0, u);
    } else {
      OrthonormalBasis(n0, &u, &v);
    }
    out.chart[seed] = chart;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const Vec3 d = triangles[t][k] - origin;
        out.flat[t][k] = {Dot(d, u), Dot(d, v)};
      }
      if (degenerate[t]) continue;
      for (const int64_t m : next[t]) {
        if (m < 0 || out.chart[m] != ~0u || degenerate[m]) continue;
        if (Dot(normal[m], n0) < kParallel) continue;
        bool on_plane = true;
        for (const Vec3& p : triangles[m])
          on_plane = on_plane && std::abs(Dot(p - origin, n0)) <= tol;
        if (!on_plane) continue;
        out.chart[m] = chart;
        stack.push_back(uint32_t(m));
      }
    }
  }
  return out;
}

}  // namespace radfarm
