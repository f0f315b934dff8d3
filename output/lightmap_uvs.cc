#include "output/lightmap_uvs.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace radfarm {
namespace {

constexpr double kPlaneTolerance = 1e-5;   // of the scene's diagonal
constexpr double kInsideTolerance = 1e-6;  // barycentric
constexpr double kParallel = 0.999;        // |cos| between the normals

// The input triangles by the grid cells their bounds touch.
class TriangleGrid {
 public:
  TriangleGrid(const std::vector<LightmapTriangle>& triangles, const Bounds3& bounds, double pad)
      : lo_(bounds.lo) {
    double extent = 0;
    for (const LightmapTriangle& t : triangles) {
      Bounds3 b;
      for (const Vec3& p : t.position) b.Extend(p);
      extent += std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z});
    }
    // About a triangle's size, but never so fine that a large one spans a million cells.
    cell_ = std::max(extent / std::max<size_t>(triangles.size(), 1), bounds.Diagonal() / 128);
    if (!(cell_ > 0)) cell_ = 1;
    for (uint32_t i = 0; i < triangles.size(); ++i) {
      Bounds3 b;
      for (const Vec3& p : triangles[i].position) b.Extend(p);
      const auto lo = Cell(b.lo - Vec3{pad, pad, pad}), hi = Cell(b.hi + Vec3{pad, pad, pad});
      for (int64_t x = lo[0]; x <= hi[0]; ++x) {
        for (int64_t y = lo[1]; y <= hi[1]; ++y) {
          for (int64_t z = lo[2]; z <= hi[2]; ++z) cells_[Key({x, y, z})].push_back(i);
        }
      }
    }
  }

  const std::vector<uint32_t>* At(const Vec3& p) const {
    const auto it = cells_.find(Key(Cell(p)));
    return it == cells_.end() ? nullptr : &it->second;
  }

 private:
  std::array<int64_t, 3> Cell(const Vec3& p) const {
    return {static_cast<int64_t>(std::floor((p.x - lo_.x) / cell_)),
            static_cast<int64_t>(std::floor((p.y - lo_.y) / cell_)),
            static_cast<int64_t>(std::floor((p.z - lo_.z) / cell_))};
  }
  static uint64_t Key(const std::array<int64_t, 3>& c) {
    return (uint64_t(c[0] + (1 << 20)) << 42) ^ (uint64_t(c[1] + (1 << 20)) << 21) ^
           uint64_t(c[2] + (1 << 20));
  }

  Vec3 lo_;
  double cell_ = 1;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

// Barycentric coordinates of p's projection on the triangle's plane.
std::array<double, 3> Barycentric(const std::array<Vec3, 3>& t, const Vec3& p) {
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0], d = p - t[0];
  const double a = Dot(e1, e1), b = Dot(e1, e2), c = Dot(e2, e2);
  const double p1 = Dot(d, e1), p2 = Dot(d, e2);
  const double det = a * c - b * b;
  const double v = (c * p1 - b * p2) / det, w = (a * p2 - b * p1) / det;
  return {1 - v - w, v, w};
}

Vec3 Normal(const std::array<Vec3, 3>& t) { return Cross(t[1] - t[0], t[2] - t[0]); }

}  // namespace

DisplayLightmapUvs LocateLightmapUvs(const DisplayMesh& mesh,
                                     const std::vector<uint32_t>& patch_object, size_t objects,
                                     const std::vector<LightmapTriangle>& triangles) {
  DisplayLightmapUvs out;
  const size_t count = mesh.triangles.size();
  out.source.assign(count, -1);
  out.uv.assign(count, {});
  out.front.assign(count, false);
  out.object_has_uv.assign(objects, false);
  Bounds3 bounds;
  for (const LightmapTriangle& t : triangles) {
    if (t.object < objects) out.object_has_uv[t.object] = true;
    for (const Vec3& p : t.position) bounds.Extend(p);
  }
  if (triangles.empty()) return out;
  const double tol = std::max(kPlaneTolerance * bounds.Diagonal(), 1e-12);
  const TriangleGrid grid(triangles, bounds, tol);
  for (size_t d = 0; d < count; ++d) {
    const uint32_t patch = d < mesh.triangle_patch.size() ? mesh.triangle_patch[d] : ~0u;
    if (patch >= patch_object.size() || patch_object[patch] >= objects) continue;
    const uint32_t object = patch_object[patch];
    if (!out.object_has_uv[object]) continue;
    std::array<Vec3, 3> corners;
    bool valid = true;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.triangles[d][k];
      valid = valid && v < mesh.positions.size();
      if (valid) corners[k] = mesh.positions[v];
    }
    const Vec3 centre = valid ? (corners[0] + corners[1] + corners[2]) / 3 : Vec3{};
    const Vec3 normal = valid ? Normal(corners) : Vec3{};
    const std::vector<uint32_t>* candidates = valid ? grid.At(centre) : nullptr;
    int64_t best = -1;
    double best_score = INFINITY;  // how far outside, then off the plane
    for (size_t i = 0; candidates != nullptr && i < candidates->size(); ++i) {
      const LightmapTriangle& t = triangles[(*candidates)[i]];
      if (t.object != object) continue;
      const Vec3 n = Normal(t.position);
      const double ln = Length(n), ld = Length(normal);
      if (!(ln > 0) || !(ld > 0) || std::abs(Dot(n, normal)) < kParallel * ln * ld) continue;
      const double off_plane = std::abs(Dot(centre - t.position[0], n)) / ln;
      if (off_plane > tol) continue;
      const std::array<double, 3> bary = Barycentric(t.position, centre);
      const double outside = -std::min({bary[0], bary[1], bary[2]});
      if (outside > kInsideTolerance) continue;
      const double score = std::max(outside, 0.0) + off_plane;
      if (score < best_score) {
        best_score = score;
        best = (*candidates)[i];
      }
    }
    if (best < 0) {
      ++out.unplaced;
      continue;
    }
    const LightmapTriangle& t = triangles[best];
    out.source[d] = best;
    out.front[d] = Dot(Normal(t.position), normal) > 0;
    for (int k = 0; k < 3; ++k) {
      const std::array<double, 3> bary = Barycentric(t.position, corners[k]);
      for (int c = 0; c < 2; ++c) {
        out.uv[d][k][c] =
            static_cast<float>(bary[0] * t.uv[0][c] + bary[1] * t.uv[1][c] + bary[2] * t.uv[2][c]);
      }
    }
  }
  return out;
}

}  // namespace radfarm
