// PatchMesh's second half: from patch radiosities to vertex radiance and display triangles.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "core/counter_rng.h"
#include "core/direct_light.h"
#include "core/point_gather.h"
#include "mesh/border_extrapolation.h"
#include "mesh/display_cut.h"
#include "mesh/display_ray_plan.h"
#include "mesh/ear_clip.h"
#include "mesh/gouraud_means.h"
#include "mesh/midpoint_split.h"
#include "mesh/patch_mesh.h"
#include "mesh/polygon.h"
#include "mesh/selective_split.h"

namespace radfarm {
namespace {

// What the display knows of each of its points besides the radiance it shows.
struct PointLight {
  std::vector<bool> held;         // gathered: its value is its own, not a stand-in for a mean
  std::vector<Rgb> irradiance;    // the direct light at the point
  std::vector<Rgb> shown_direct;  // rho times that
};

// What a level's points will cost under an allowance (display_ray_plan.h): each point's shadow
// rays and each gathering point's rays as the display's points spent them on average.
struct LevelRays {
  std::optional<uint64_t> allowance;
  double direct_per_point = 0;
  double gather_per_point = 0;
  uint32_t gather_rays = kPointGatherRays;
};

// Cuts the triangles of `fine` where the light bends, and sets each new point to its own light.
// A triangle whose corners all hold their own light (held: gathered) is cut where their light
// differs by more than CutContrast (display_cut.h) of the brightest; any other where the direct
// light shown at its corners does, a shadow's edge or a lamp's fall-off. A new point between two
// held ones gathers (rho times the direct and the gathered light) and is held; any other shows the
// direct light at itself plus the rest interpolated between its edge's ends. Returns the number of
// points added; *levels the levels cut, *rays increased by their rays. A level whose points would
// take the rays past the allowance is not cut, nor any after it.
uint64_t RefineWhereLightBends(const PatchScene& scene, const RayCaster& caster,
                               const DirectLight& direct_light, const std::vector<Rgb>& outgoing,
                               const PatchCornerOffsets& corners, const SecondBounce& second,
                               const PatchMesh::VertexDirectLight& direct, const LevelRays& budget,
                               const PatchMesh::DisplayProgress& progress, DisplayMesh* fine,
                               PointLight* light, int* levels, uint64_t* rays) {
  std::vector<bool>& held = light->held;
  std::vector<Rgb>& shown_direct = light->shown_direct;
  uint64_t points_added = 0;
  for (int level = 1; level <= kDisplayRefineLevels; ++level) {
    std::vector<bool> marked(fine->triangles.size(), false);
    bool any = false;
    for (size_t t = 0; t < fine->triangles.size(); ++t) {
      if (scene.patches[fine->triangle_patch[t]].emission.Max() > 0) continue;
      const std::array<uint32_t, 3>& v = fine->triangles[t];
      const bool all_held = held[v[0]] && held[v[1]] && held[v[2]];
      double lo = INFINITY, hi = -INFINITY, direct_lo = INFINITY, direct_hi = -INFINITY;
      for (uint32_t n : v) {
        lo = std::min(lo, fine->radiance[n].Sum());
        hi = std::max(hi, fine->radiance[n].Sum());
        direct_lo = std::min(direct_lo, shown_direct[n].Sum());
        direct_hi = std::max(direct_hi, shown_direct[n].Sum());
      }
      const double contrast = CutContrast(fine->positions[v[0]], fine->positions[v[1]],
                                          fine->positions[v[2]], all_held);
      marked[t] = (all_held ? hi - lo : direct_hi - direct_lo) > contrast * hi;
      any = any || marked[t];
    }
    if (!any) break;
    if (budget.allowance) {
      // A marked triangle's three edges each get a point, shared by two triangles at most: when
      // even that many points' direct light would not fit, the split is not worth making.
      const double at_least =
          1.5 * double(std::count(marked.begin(), marked.end(), true)) * budget.direct_per_point;
      if (double(*rays) + at_least > double(*budget.allowance)) break;
    }
    SelectiveSplit split = SplitMarked(*fine, std::move(marked));
    DisplayMesh& mesh = split.mesh;
    const size_t added = split.edge_ends.size();
    // Each new point: a hair toward the centroids of the triangles around it, facing as their
    // patches do, with their reflectance.
    std::vector<Vec3> centroids(added), normals(added);
    std::vector<Rgb> rho(added);
    std::vector<double> weight(added, 0.0);
    std::vector<uint32_t> around(added, 0);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const std::array<uint32_t, 3>& v = mesh.triangles[t];
      const Vec3 centroid =
          (mesh.positions[v[0]] + mesh.positions[v[1]] + mesh.positions[v[2]]) / 3.0;
      const Patch& p = scene.patches[mesh.triangle_patch[t]];
      for (uint32_t n : v) {
        if (n < split.first_new) continue;
        const size_t k = n - split.first_new;
        centroids[k] = centroids[k] + centroid;
        normals[k] = normals[k] + p.normal * p.area;
        rho[k] += p.reflectance * p.area;
        weight[k] += p.area;
        ++around[k];
      }
    }
    std::vector<ReceiverPoint> points(added);
    for (size_t k = 0; k < added; ++k) {
      const Vec3& at = mesh.positions[split.first_new + k];
      points[k] = {at + (centroids[k] / double(around[k]) - at) * kVertexInset,
                   normals[k] / Length(normals[k])};
      rho[k] = rho[k] / weight[k];
    }
    std::vector<bool> gathers(added);
    for (size_t k = 0; k < added; ++k) {
      gathers[k] = held[split.edge_ends[k][0]] && held[split.edge_ends[k][1]];
    }
    if (budget.allowance) {
      const double cost =
          double(added) * budget.direct_per_point +
          double(std::count(gathers.begin(), gathers.end(), true)) * budget.gather_per_point;
      if (double(*rays) + cost > double(*budget.allowance)) break;
    }
    if (progress) progress({PatchMesh::DisplayStep::kRefining, added, level});
    const uint64_t seed = HashWords(direct.seed, uint64_t(level));
    const std::vector<Rgb> gathered =
        GatherLight(caster, outgoing, points, gathers, seed, direct.threads, budget.gather_rays,
                    &corners, &second, rays);
    const std::vector<Rgb> irradiance =
        PointsDirectLight(direct_light, points, seed, direct.threads, rays);
    held.resize(mesh.positions.size(), false);
    shown_direct.resize(mesh.positions.size());
    light->irradiance.resize(mesh.positions.size());
    for (size_t k = 0; k < added; ++k) {
      const uint32_t n = split.first_new + k;
      const auto [a, b] = split.edge_ends[k];
      const Rgb shown = rho[k] * irradiance[k];
      if (gathers[k]) {
        mesh.radiance[n] = rho[k] * gathered[k] + shown;
      } else {
        // The split set it to its ends' mean: their direct light's mean gives way to its own.
        mesh.radiance[n] += shown - (shown_direct[a] + shown_direct[b]) * 0.5;
      }
      held[n] = gathers[k];
      shown_direct[n] = shown;
      light->irradiance[n] = irradiance[k];
    }
    *fine = std::move(mesh);
    points_added += added;
    *levels = level;
  }
  return points_added;
}

}  // namespace

void PatchMesh::StoreSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot) {
  OmMesh& mesh = *data_.mesh;
  const PatchProperties& p = data_.props;
  const size_t faces = data_.scene.patches.size();
  if (radiosity.size() != faces || unshot.size() != faces) {
    std::fprintf(stderr,
                 "PatchMesh::SetSolution: %zu radiosities, %zu unshot values, %zu patches\n",
                 radiosity.size(), unshot.size(), faces);
    std::abort();
  }
  for (uint32_t f = 0; f < faces; ++f) {
    const OmMesh::FaceHandle fh = mesh.face_handle(f);
    mesh.property(p.radiosity, fh) = radiosity[f];
    mesh.property(p.unshot, fh) = unshot[f];
  }
}

template <typename Visit>
void PatchMesh::ForEachVertexPatch(Visit&& visit) const {
  const OmMesh& mesh = *data_.mesh;
  for (uint32_t f = 0; f < data_.scene.patches.size(); ++f) {
    for (OmMesh::VertexHandle vh : mesh.fv_range(mesh.face_handle(f))) {
      visit(mesh.property(data_.props.group, vh), f);
    }
  }
  for (const EdgePoint& e : data_.edge_points) visit(e.group, e.face);
}

std::vector<Rgb> PatchMesh::VertexAverages(const std::vector<Rgb>& per_patch) const {
  std::vector<Rgb> sum(data_.group_vertex.size());
  std::vector<double> weight(data_.group_vertex.size(), 0.0);
  ForEachVertexPatch([&](uint32_t group, uint32_t face) {
    const double area = data_.scene.patches[face].area;
    sum[group] += per_patch[face] * area;
    weight[group] += area;
  });
  for (size_t g = 0; g < sum.size(); ++g) sum[g] = weight[g] > 0 ? sum[g] / weight[g] : Rgb();
  return sum;
}

void PatchMesh::SetVertexRadiance(const std::vector<Rgb>& value) {
  OmMesh& mesh = *data_.mesh;
  for (OmMesh::VertexHandle vh : mesh.vertices()) {
    mesh.property(data_.props.radiance, vh) = value[mesh.property(data_.props.group, vh)];
  }
}

void PatchMesh::SetSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot) {
  split_display_.reset();
  StoreSolution(radiosity, unshot);
  std::vector<Rgb> value = VertexAverages(radiosity);
  ExtrapolateBorders(FaceRings(), &value);
  SetVertexRadiance(value);
}

PatchCornerOffsets PatchMesh::CornerDirectOffsets(const std::vector<Rgb>& irradiance,
                                                  const std::vector<uint32_t>& point_of,
                                                  const std::vector<Rgb>& patch_direct) const {
  const OmMesh& mesh = *data_.mesh;
  const std::vector<Patch>& patches = data_.scene.patches;
  PatchCornerOffsets corners;
  corners.scene = &data_.scene;
  corners.offsets.resize(patches.size());
  for (uint32_t f = 0; f < patches.size(); ++f) {
    const Patch& p = patches[f];
    for (OmMesh::VertexHandle vh : mesh.fv_range(mesh.face_handle(f))) {
      const uint32_t point = point_of[mesh.property(data_.props.group, vh)];
      if (point >= irradiance.size()) continue;  // no point: the offset stays 0
      // The patch's corner at this vertex (welding may have moved it by a tolerance).
      const Vec3 at = FromOm(mesh.point(vh));
      int corner = 0;
      for (int k = 1; k < p.corner_count; ++k) {
        if (Length(p.corners[k] - at) < Length(p.corners[corner] - at)) corner = k;
      }
      corners.offsets[f][corner] = p.reflectance * (irradiance[point] - patch_direct[f]);
    }
    // The offsets shape the light over the patch but keep its mean, the solution's: their
    // interpolation's mean (over the triangles InterpolateCornerOffsets uses) is taken off.
    std::array<Rgb, 4>& o = corners.offsets[f];
    const double a1 = Length(Cross(p.corners[1] - p.corners[0], p.corners[2] - p.corners[0]));
    const double a2 = p.corner_count == 4
                          ? Length(Cross(p.corners[2] - p.corners[0], p.corners[3] - p.corners[0]))
                          : 0.0;
    if (!(a1 + a2 > 0)) continue;
    const Rgb mean =
        ((o[0] + o[1] + o[2]) * a1 + (o[0] + o[2] + o[3]) * a2) * (1 / (3 * (a1 + a2)));
    for (int k = 0; k < p.corner_count; ++k) o[k] = o[k] - mean;
  }
  return corners;
}

void PatchMesh::SetSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot,
                            const VertexDirectLight& direct, const DisplayProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  split_display_.reset();
  display_stats_ = {};
  StoreSolution(radiosity, unshot);
  const std::vector<Patch>& patches = data_.scene.patches;
  if (direct.patch_direct.size() != patches.size()) {
    std::fprintf(stderr, "PatchMesh::SetSolution: %zu direct light values, %zu patches\n",
                 direct.patch_direct.size(), patches.size());
    std::abort();
  }
  // What the patch averages hold besides the direct light: emission and bounced light, smooth.
  std::vector<Rgb> rest(patches.size()), reflectance(patches.size());
  for (size_t f = 0; f < patches.size(); ++f) {
    rest[f] = radiosity[f] - patches[f].reflectance * direct.patch_direct[f];
    reflectance[f] = patches[f].reflectance;
  }
  std::vector<Rgb> vertex_rest = VertexAverages(rest);
  ExtrapolateBorders(FaceRings(), &vertex_rest);
  const std::vector<Rgb> vertex_rho = VertexAverages(reflectance);

  // Each vertex's point: a hair inside the patches around it (toward their centres), so a vertex
  // on a crease or at the foot of a wall sees the light as the surface beside it does.
  const size_t groups = data_.group_vertex.size();
  std::vector<Vec3> centre_sum(groups), normal_sum(groups);
  std::vector<uint32_t> count(groups, 0);
  // Emitters show their emission: their points keep the average.
  auto keeps_average = [](const Patch& p) { return p.emission.Max() > 0; };
  std::vector<bool> average(groups, false);
  ForEachVertexPatch([&](uint32_t group, uint32_t face) {
    centre_sum[group] = centre_sum[group] + patches[face].centre;
    normal_sum[group] = normal_sum[group] + patches[face].normal * patches[face].area;
    average[group] = average[group] || keeps_average(patches[face]);
    ++count[group];
  });
  constexpr uint32_t kNoPoint = ~uint32_t{0};
  std::vector<ReceiverPoint> points;
  std::vector<bool> may_gather;                      // per point
  std::vector<uint32_t> point_of(groups, kNoPoint);  // per display vertex
  for (uint32_t g = 0; g < groups; ++g) {
    const double length = Length(normal_sum[g]);
    if (count[g] == 0 || !(length > 0)) continue;
    const Vec3 at = FromOm(data_.mesh->point(data_.group_vertex[g]));
    const Vec3 inward = centre_sum[g] / double(count[g]) - at;
    point_of[g] = static_cast<uint32_t>(points.size());
    points.push_back({at + inward * kVertexInset, normal_sum[g] / length});
    may_gather.push_back(!average[g]);
  }

  // The display cut at its midpoints; the rest there is the mean of its edge's ends.
  SetVertexRadiance(vertex_rest);
  MidpointSplit split = SplitAtMidpoints(PatchDisplayMesh());
  DisplayMesh& fine = split.mesh;
  const size_t midpoints = split.edge_ends.size();
  // Each midpoint's point: a hair toward the centroids of the triangles beside its edge, facing as
  // their patches do on average; and its reflectance, their patches' on average.
  std::vector<Vec3> mid_centroids(midpoints), mid_normals(midpoints);
  std::vector<Rgb> mid_rho(midpoints);
  std::vector<double> mid_weight(midpoints, 0.0);
  std::vector<bool> mid_average(midpoints, false);
  std::vector<uint32_t> mid_triangles(midpoints, 0);
  for (size_t t = 0; t < split.triangle_midpoints.size(); ++t) {
    const std::array<uint32_t, 3>& v = fine.triangles[4 * t + 3];  // the middle triangle
    const Vec3 centroid =
        (fine.positions[v[0]] + fine.positions[v[1]] + fine.positions[v[2]]) / 3.0;
    const Patch& p = patches[fine.triangle_patch[4 * t]];
    for (uint32_t m : split.triangle_midpoints[t]) {
      const uint32_t k = m - split.coarse_vertices;
      mid_centroids[k] = mid_centroids[k] + centroid;
      mid_normals[k] = mid_normals[k] + p.normal * p.area;
      mid_rho[k] += p.reflectance * p.area;
      mid_weight[k] += p.area;
      mid_average[k] = mid_average[k] || keeps_average(p);
      ++mid_triangles[k];
    }
  }
  std::vector<Rgb> rho = vertex_rho;
  rho.resize(groups + midpoints);
  point_of.resize(groups + midpoints, kNoPoint);
  for (size_t k = 0; k < midpoints; ++k) {
    const double length = Length(mid_normals[k]);
    if (!(length > 0) || !(mid_weight[k] > 0)) continue;
    const Vec3& at = fine.positions[split.coarse_vertices + k];
    const Vec3 inward = mid_centroids[k] / double(mid_triangles[k]) - at;
    rho[groups + k] = mid_rho[k] / mid_weight[k];
    point_of[groups + k] = static_cast<uint32_t>(points.size());
    points.push_back({at + inward * kVertexInset, mid_normals[k] / length});
    may_gather.push_back(!mid_average[k]);
  }

  // Near other surfaces (a patch size and a half: the mesh's, not the patches', as a sliver cut
  // along a lamp's outline is near the lamp too), the rest at the point itself
  // (core/point_gather.h): rho times the light gathered from the patches, less the emitters' where
  // the direct light holds it. Such points hold their value: the step toward the patch means
  // below is for averages.
  // One caster and one DirectLight for every gather and every level's points.
  const RayCaster caster(data_.scene);
  const std::optional<uint64_t> allowance =
      direct.ray_allowance > 0 ? std::optional<uint64_t>(direct.ray_allowance) : std::nullopt;
  uint64_t& rays = display_stats_.rays;
  DisplayDirectChoice fitted =
      FitDisplayDirectLight(data_.scene, caster, points, direct.emitters, direct.rays_per_light,
                            allowance, direct.seed, direct.threads);
  rays += fitted.probe_rays;
  if (!fitted.light) {
    // Not even the fewest shadow rays at every point fit: the patches' averages, for free.
    const DisplayStats stats = display_stats_;
    SetSolution(radiosity, unshot);
    display_stats_ = stats;
    display_stats_.averaged = true;
    display_stats_.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return;
  }
  const DirectLight& direct_light = *fitted.light;
  display_stats_.rays_per_light = fitted.rays_per_light;
  std::vector<bool> gather =
      NearOtherSurfaces(data_.scene, caster, points, kGatherBand * patch_size_, direct.threads);
  for (size_t i = 0; i < points.size(); ++i) gather[i] = gather[i] && may_gather[i];
  std::vector<Rgb> outgoing = radiosity;
  if (direct.emitters) {
    for (size_t f = 0; f < patches.size(); ++f) outgoing[f] = outgoing[f] - patches[f].emission;
  }
  if (progress) progress({DisplayStep::kDirectLight, points.size(), 0});
  const uint64_t before_direct = rays;
  const std::vector<Rgb> irradiance =
      PointsDirectLight(direct_light, points, direct.seed, direct.threads, &rays);
  LevelRays level_rays;
  level_rays.allowance = allowance;
  level_rays.direct_per_point =
      points.empty() ? 0.0 : double(rays - before_direct) / double(points.size());
  const PatchCornerOffsets corners = CornerDirectOffsets(irradiance, point_of, direct.patch_direct);
  // What of each patch's light a gathering ray that meets it near gathers again instead: its
  // bounced part, the rest less emission (core/point_gather.h).
  SecondBounce second;
  second.scene = &data_.scene;
  second.bounced.resize(patches.size());
  for (size_t f = 0; f < patches.size(); ++f) second.bounced[f] = rest[f] - patches[f].emission;
  // What the direct light left of the allowance.
  const std::optional<uint64_t> left =
      allowance ? std::optional<uint64_t>(*allowance - std::min(*allowance, rays)) : std::nullopt;
  const DisplayGatherChoice gathering = FitDisplayGather(caster, outgoing, points, gather, corners,
                                                         second, left, direct.seed, direct.threads);
  rays += gathering.probe_rays;
  if (gathering.rays == 0) gather.assign(gather.size(), false);
  const uint64_t gathering_points = uint64_t(std::count(gather.begin(), gather.end(), true));
  if (progress) progress({DisplayStep::kGathering, gathering_points, 0});
  const uint64_t before_gather = rays;
  const std::vector<Rgb> gathered =
      GatherLight(caster, outgoing, points, gather, direct.seed, direct.threads, gathering.rays,
                  &corners, &second, &rays);
  display_stats_.gather_rays = gathering_points > 0 ? gathering.rays : 0;
  level_rays.gather_rays = gathering.rays;
  level_rays.gather_per_point =
      gathering_points > 0 ? double(rays - before_gather) / double(gathering_points) : 0.0;
  PointLight light;
  light.held.assign(groups + midpoints, false);
  for (size_t n = 0; n < groups + midpoints; ++n) {
    if (point_of[n] != kNoPoint && gather[point_of[n]]) {
      fine.radiance[n] = rho[n] * gathered[point_of[n]];
      light.held[n] = true;
      ++display_stats_.gathered;
    }
  }

  light.irradiance.resize(groups + midpoints);
  light.shown_direct.resize(groups + midpoints);
  for (size_t n = 0; n < groups + midpoints; ++n) {
    if (point_of[n] != kNoPoint) light.irradiance[n] = irradiance[point_of[n]];
    light.shown_direct[n] = rho[n] * light.irradiance[n];
    fine.radiance[n] += light.shown_direct[n];
  }

  // Each patch's mean direct light over its triangles, each by the midpoint rule (the mean of its
  // edge midpoints' values, exact for quadratics).
  std::vector<Rgb> direct_sum(patches.size());
  std::vector<double> area(patches.size(), 0.0);
  for (size_t t = 0; t < split.triangle_midpoints.size(); ++t) {
    const std::array<uint32_t, 3>& m = split.triangle_midpoints[t];
    const std::array<uint32_t, 3>& v = fine.triangles[4 * t + 3];  // a quarter of the triangle
    const Vec3& a = fine.positions[v[0]];
    const double twice_area = Length(Cross(fine.positions[v[1]] - a, fine.positions[v[2]] - a));
    const uint32_t f = fine.triangle_patch[4 * t];
    direct_sum[f] +=
        (light.irradiance[m[0]] + light.irradiance[m[1]] + light.irradiance[m[2]]) * twice_area;
    area[f] += twice_area;
  }

  display_stats_.added =
      RefineWhereLightBends(data_.scene, caster, direct_light, outgoing, corners, second, direct,
                            level_rays, progress, &fine, &light, &display_stats_.levels, &rays);
  // A patch the refinement cut holds a shadow's edge or a steep rise, which three midpoints per
  // triangle miss: its mean is the refined triangles' (each the mean of its corners).
  const uint32_t first_new = static_cast<uint32_t>(groups + midpoints);
  std::vector<bool> refined(patches.size(), false);
  for (size_t t = 0; t < fine.triangles.size(); ++t) {
    for (uint32_t n : fine.triangles[t]) {
      if (n >= first_new) refined[fine.triangle_patch[t]] = true;
    }
  }
  for (size_t f = 0; f < patches.size(); ++f) {
    if (refined[f]) direct_sum[f] = Rgb(), area[f] = 0;
  }
  for (size_t t = 0; t < fine.triangles.size(); ++t) {
    const uint32_t f = fine.triangle_patch[t];
    if (!refined[f]) continue;
    const std::array<uint32_t, 3>& v = fine.triangles[t];
    const Vec3& a = fine.positions[v[0]];
    const double twice_area = Length(Cross(fine.positions[v[1]] - a, fine.positions[v[2]] - a));
    direct_sum[f] +=
        (light.irradiance[v[0]] + light.irradiance[v[1]] + light.irradiance[v[2]]) * twice_area;
    area[f] += twice_area;
  }
  // Then one step toward each patch's mean light: the rest as solved plus rho times that mean.
  std::vector<Rgb> target(patches.size());
  std::vector<bool> moves(patches.size());
  for (size_t f = 0; f < patches.size(); ++f) {
    moves[f] = patches[f].emission.Max() == 0 && area[f] > 0;  // an emitter shows its emission
    if (moves[f]) target[f] = rest[f] + patches[f].reflectance * (direct_sum[f] / (3 * area[f]));
  }
  StepTowardPatchMeans(&fine, target, moves, light.held);
  display_stats_.points = points.size() + display_stats_.added;
  display_stats_.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  SetVertexRadiance(std::vector<Rgb>(fine.radiance.begin(), fine.radiance.begin() + groups));
  split_display_ = std::move(fine);
}

std::vector<std::vector<uint32_t>> PatchMesh::FaceRings() const {
  const OmMesh& mesh = *data_.mesh;
  const PatchProperties& p = data_.props;
  std::vector<std::vector<uint32_t>> rings(data_.scene.patches.size());
  auto edge_point = data_.edge_points.begin();
  for (uint32_t f = 0; f < rings.size(); ++f) {
    std::array<OmMesh::VertexHandle, 4> corners;
    const int n = FaceCorners(mesh, mesh.face_handle(f), &corners);
    for (int j = 0; j < n; ++j) {
      rings[f].push_back(mesh.property(p.group, corners[j]));
      for (; edge_point != data_.edge_points.end() && edge_point->face == f &&
             edge_point->edge == static_cast<uint32_t>(j);
           ++edge_point) {
        rings[f].push_back(edge_point->group);
      }
    }
  }
  return rings;
}

DisplayMesh PatchMesh::MakeDisplayMesh() const {
  return split_display_ ? *split_display_ : PatchDisplayMesh();
}

DisplayMesh PatchMesh::PatchDisplayMesh() const {
  const OmMesh& mesh = *data_.mesh;
  const PatchProperties& p = data_.props;
  DisplayMesh out;
  for (OmMesh::VertexHandle vh : data_.group_vertex) {
    out.positions.push_back(FromOm(mesh.point(vh)));
    out.radiance.push_back(mesh.property(p.radiance, vh));
  }
  const std::vector<std::vector<uint32_t>> rings = FaceRings();
  for (const Patch& patch : data_.scene.patches) {
    if (!patch.two_sided) continue;
    out.patch_front_only.resize(data_.scene.patches.size());
    break;
  }
  if (!out.patch_front_only.empty()) {
    for (uint32_t f = 0; f < data_.scene.patches.size(); ++f) {
      out.patch_front_only[f] = data_.scene.patches[f].two_sided;
    }
  }
  std::vector<Vec3> ring_positions;
  for (uint32_t f = 0; f < data_.scene.patches.size(); ++f) {
    const std::vector<uint32_t>& ring = rings[f];
    const int n = data_.scene.patches[f].corner_count;
    if (static_cast<int>(ring.size()) == n) {
      // The split the Patch contract names for quads: (0, 1, 2) and (0, 2, 3).
      for (int j = 1; j + 1 < n; ++j) {
        out.triangles.push_back({ring[0], ring[j], ring[j + 1]});
        out.triangle_patch.push_back(f);
      }
      continue;
    }
    ring_positions.clear();
    for (uint32_t g : ring) ring_positions.push_back(out.positions[g]);
    const EarClipResult clip =
        EarClip(ProjectToPlane(ring_positions, ring_positions[0], data_.scene.patches[f].normal));
    for (const auto& t : clip.triangles) {
      out.triangles.push_back({ring[t[0]], ring[t[1]], ring[t[2]]});
      out.triangle_patch.push_back(f);
    }
  }
  return out;
}

}  // namespace radfarm
