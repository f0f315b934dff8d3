#include "mesh/polygon_split.h"

#include <algorithm>
#include <cmath>

#include "mesh/ear_clip.h"
#include "mesh/polygon.h"

namespace radfarm {
namespace {

// Caps one direction's count; the patch-count limit in patch_mesh.cc rejects such scenes anyway.
constexpr double kMaxDivisions = 1 << 20;

double LongestEdge(const std::array<Vec3, 3>& t) {
  return std::max({Length(t[1] - t[0]), Length(t[2] - t[1]), Length(t[0] - t[2])});
}

// Point (u, v) of the bilinear patch; with v = 0 or 1 (or u) the unused corners get weight 0 and
// the edge points come out the same from both neighbouring cells.
Vec3 Bilinear(const std::array<Vec3, 4>& q, double u, double v) {
  return q[0] * ((1 - u) * (1 - v)) + q[1] * (u * (1 - v)) + q[2] * (u * v) + q[3] * ((1 - u) * v);
}

void EmitGrid(const SplitPlan& plan, std::vector<PieceCorners>* out) {
  const double n = static_cast<double>(plan.n), m = static_cast<double>(plan.m);
  for (uint64_t j = 0; j < plan.m; ++j) {
    for (uint64_t i = 0; i < plan.n; ++i) {
      const double u0 = static_cast<double>(i) / n, u1 = static_cast<double>(i + 1) / n;
      const double v0 = static_cast<double>(j) / m, v1 = static_cast<double>(j + 1) / m;
      out->push_back({{Bilinear(plan.quad, u0, v0), Bilinear(plan.quad, u1, v0),
                       Bilinear(plan.quad, u1, v1), Bilinear(plan.quad, u0, v1)},
                      4});
    }
  }
}

// Barycentric lattice point (i, j) of a triangle split k ways, written as a weighted sum of the
// corners so that points on a shared edge round the same way from both triangles.
Vec3 Lattice(const std::array<Vec3, 3>& t, uint64_t k, uint64_t i, uint64_t j) {
  const double kd = static_cast<double>(k);
  return (t[0] * static_cast<double>(k - i - j) + t[1] * static_cast<double>(i) +
          t[2] * static_cast<double>(j)) /
         kd;
}

void EmitTriangle(const std::array<Vec3, 3>& t, uint64_t k, std::vector<PieceCorners>* out) {
  for (uint64_t j = 0; j < k; ++j) {
    for (uint64_t i = 0; i + j < k; ++i) {
      out->push_back(
          {{Lattice(t, k, i, j), Lattice(t, k, i + 1, j), Lattice(t, k, i, j + 1), {}}, 3});
      if (i + j + 2 <= k) {
        out->push_back(
            {{Lattice(t, k, i + 1, j), Lattice(t, k, i + 1, j + 1), Lattice(t, k, i, j + 1), {}},
             3});
      }
    }
  }
}

}  // namespace

uint64_t Divisions(double length, double patch_size) {
  const double d = std::ceil(length / patch_size - 1e-9);
  return static_cast<uint64_t>(std::clamp(d, 1.0, kMaxDivisions));
}

SplitPlan PlanSplit(const std::vector<Vec3>& corners, const Vec3& unit_normal, double patch_size,
                    double tol) {
  SplitPlan plan;
  if (corners.size() == 4 && MaxPlaneDistance(corners, unit_normal) <= tol &&
      IsStrictlyConvex(corners, unit_normal)) {
    std::copy(corners.begin(), corners.end(), plan.quad.begin());
    const auto& q = plan.quad;
    plan.n = Divisions(std::max(Length(q[1] - q[0]), Length(q[2] - q[3])), patch_size);
    plan.m = Divisions(std::max(Length(q[3] - q[0]), Length(q[2] - q[1])), patch_size);
    return plan;
  }
  if (corners.size() == 3) {
    plan.triangles.push_back({corners[0], corners[1], corners[2]});
  } else {
    const EarClipResult clip = EarClip(ProjectToPlane(corners, corners[0], unit_normal));
    plan.simple = clip.simple;
    for (const auto& t : clip.triangles) {
      plan.triangles.push_back({corners[t[0]], corners[t[1]], corners[t[2]]});
    }
  }
  double longest = 0;
  for (const auto& t : plan.triangles) longest = std::max(longest, LongestEdge(t));
  plan.k = Divisions(longest, kTriangleEdgeFactor * patch_size);
  return plan;
}

void EmitPieces(const SplitPlan& plan, std::vector<PieceCorners>* out) {
  if (plan.n > 0) {
    EmitGrid(plan, out);
    return;
  }
  for (const auto& t : plan.triangles) EmitTriangle(t, plan.k, out);
}

}  // namespace radfarm
