#include "display/light_bends.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "display/display_cut.h"
#include "display/display_settings.h"

namespace radfarm {
namespace {

// The triangles to cut; empty where none is.
std::vector<bool> MarkWhereLightBends(const PatchScene& scene, const DisplayMesh& fine,
                                      const PointLight& light) {
  std::vector<bool> marked(fine.triangles.size(), false);
  bool any = false;
  for (size_t t = 0; t < fine.triangles.size(); ++t) {
    if (scene.patches[fine.triangle_patch[t]].emission.Max() > 0) continue;
    const std::array<uint32_t, 3>& v = fine.triangles[t];
    const bool all_held = light.held[v[0]] && light.held[v[1]] && light.held[v[2]];
    double lo = INFINITY, hi = -INFINITY, direct_lo = INFINITY, direct_hi = -INFINITY;
    for (uint32_t n : v) {
      lo = std::min(lo, fine.radiance[n].Sum());
      hi = std::max(hi, fine.radiance[n].Sum());
      direct_lo = std::min(direct_lo, light.shown_direct[n].Sum());
      direct_hi = std::max(direct_hi, light.shown_direct[n].Sum());
    }
    const double contrast =
        CutContrast(fine.positions[v[0]], fine.positions[v[1]], fine.positions[v[2]], all_held);
    marked[t] = (all_held ? hi - lo : direct_hi - direct_lo) > contrast * hi;
    any = any || marked[t];
  }
  if (!any) marked.clear();
  return marked;
}

// Each new point of the split: a hair toward the centroids of the triangles around it, facing as
// their patches do, with their reflectance.
void PlaceNewPoints(const PatchScene& scene, LevelCut* cut) {
  const DisplayMesh& mesh = cut->split.mesh;
  const uint32_t first_new = cut->split.first_new;
  const size_t added = cut->split.edge_ends.size();
  std::vector<Vec3> centroids(added), normals(added);
  std::vector<Rgb>& rho = cut->rho;
  rho.assign(added, Rgb());
  std::vector<double> weight(added, 0.0);
  std::vector<uint32_t> around(added, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::array<uint32_t, 3>& v = mesh.triangles[t];
    const Vec3 centroid =
        (mesh.positions[v[0]] + mesh.positions[v[1]] + mesh.positions[v[2]]) / 3.0;
    const Patch& p = scene.patches[mesh.triangle_patch[t]];
    for (uint32_t n : v) {
      if (n < first_new) continue;
      const size_t k = n - first_new;
      centroids[k] = centroids[k] + centroid;
      normals[k] = normals[k] + p.normal * p.area;
      rho[k] += p.reflectance * p.area;
      weight[k] += p.area;
      ++around[k];
    }
  }
  cut->points.resize(added);
  for (size_t k = 0; k < added; ++k) {
    const Vec3& at = mesh.positions[first_new + k];
    cut->points[k] = {at + (centroids[k] / double(around[k]) - at) * kVertexInset,
                      normals[k] / Length(normals[k])};
    rho[k] = rho[k] / weight[k];
  }
}

}  // namespace

std::optional<LevelCut> CutWhereLightBends(const PatchScene& scene, const DisplayMesh& fine,
                                           const PointLight& light, const LevelRays& budget,
                                           uint64_t rays) {
  std::vector<bool> marked = MarkWhereLightBends(scene, fine, light);
  if (marked.empty()) return std::nullopt;
  if (budget.allowance) {
    // A marked triangle's three edges each get a point, shared by two triangles at most: when
    // even that many points' direct light would not fit, the split is not worth making.
    const double at_least =
        1.5 * double(std::count(marked.begin(), marked.end(), true)) * budget.direct_per_point;
    if (double(rays) + at_least > double(*budget.allowance)) return std::nullopt;
  }
  LevelCut cut{SplitMarked(fine, std::move(marked)), {}, {}, {}};
  PlaceNewPoints(scene, &cut);
  const size_t added = cut.split.edge_ends.size();
  cut.gathers.resize(added);
  for (size_t k = 0; k < added; ++k) {
    cut.gathers[k] = light.held[cut.split.edge_ends[k][0]] && light.held[cut.split.edge_ends[k][1]];
  }
  if (budget.allowance) {
    const double cost =
        double(added) * budget.direct_per_point +
        double(std::count(cut.gathers.begin(), cut.gathers.end(), true)) * budget.gather_per_point;
    if (double(rays) + cost > double(*budget.allowance)) return std::nullopt;
  }
  return cut;
}

void ApplyLevelCut(LevelCut cut, const std::vector<Rgb>& gathered,
                   const std::vector<Rgb>& irradiance, DisplayMesh* fine, PointLight* light) {
  DisplayMesh& mesh = cut.split.mesh;
  std::vector<bool>& held = light->held;
  std::vector<Rgb>& shown_direct = light->shown_direct;
  held.resize(mesh.positions.size(), false);
  shown_direct.resize(mesh.positions.size());
  light->irradiance.resize(mesh.positions.size());
  for (size_t k = 0; k < cut.points.size(); ++k) {
    const uint32_t n = cut.split.first_new + uint32_t(k);
    const auto [a, b] = cut.split.edge_ends[k];
    const Rgb shown = cut.rho[k] * irradiance[k];
    if (cut.gathers[k]) {
      mesh.radiance[n] = cut.rho[k] * gathered[k] + shown;
    } else {
      // The split set it to its ends' mean: their direct light's mean gives way to its own.
      mesh.radiance[n] += shown - (shown_direct[a] + shown_direct[b]) * 0.5;
    }
    held[n] = cut.gathers[k];
    shown_direct[n] = shown;
    light->irradiance[n] = irradiance[k];
  }
  *fine = std::move(mesh);
}

}  // namespace radfarm
