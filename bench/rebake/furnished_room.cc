#include "bench/rebake/furnished_room.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "reference/path_tracer.h"
#include "reference/reference_scene.h"

namespace radfarm::bench {
namespace {

uint32_t AddMaterial(InputScene* scene, Rgb diffuse, Rgb emission) {
  scene->materials.push_back(
      {"m" + std::to_string(scene->materials.size()), diffuse, emission, false});
  return uint32_t(scene->materials.size() - 1);
}

// A quad with corners counter-clockwise about its front.
void AddQuad(InputScene* scene, const std::array<Vec3, 4>& corners, uint32_t material) {
  InputFace face;
  for (const Vec3& c : corners) {
    face.indices.push_back(uint32_t(scene->positions.size()));
    scene->positions.push_back(c);
  }
  face.material = material;
  scene->faces.push_back(face);
}

// A box [lo, hi] standing on the floor: the five faces that show, facing out.
void AddBlock(InputScene* scene, Vec3 lo, Vec3 hi, uint32_t m) {
  const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  AddQuad(scene, {Vec3{x0, y0, z1}, Vec3{x1, y0, z1}, Vec3{x1, y1, z1}, Vec3{x0, y1, z1}}, m);
  AddQuad(scene, {Vec3{x1, y0, z0}, Vec3{x1, y1, z0}, Vec3{x1, y1, z1}, Vec3{x1, y0, z1}}, m);
  AddQuad(scene, {Vec3{x0, y0, z0}, Vec3{x0, y0, z1}, Vec3{x0, y1, z1}, Vec3{x0, y1, z0}}, m);
  AddQuad(scene, {Vec3{x0, y1, z0}, Vec3{x0, y1, z1}, Vec3{x1, y1, z1}, Vec3{x1, y1, z0}}, m);
  AddQuad(scene, {Vec3{x0, y0, z0}, Vec3{x1, y0, z0}, Vec3{x1, y0, z1}, Vec3{x0, y0, z1}}, m);
}

}  // namespace

InputScene FurnishedRoom(const RoomChange& change) {
  InputScene scene;
  scene.path = "furnished-room";
  const double w = 4, h = 3;
  const uint32_t floor = AddMaterial(&scene, {0.4, 0.4, 0.4}, {});
  const uint32_t wall = AddMaterial(&scene, change.wall, {});
  const uint32_t table = AddMaterial(&scene, change.table, {});
  const uint32_t cupboard = AddMaterial(&scene, {0.7, 0.7, 0.6}, {});
  const Vec3 p[8] = {{0, 0, 0}, {w, 0, 0}, {w, w, 0}, {0, w, 0},
                     {0, 0, h}, {w, 0, h}, {w, w, h}, {0, w, h}};
  AddQuad(&scene, {p[0], p[1], p[2], p[3]}, floor);
  AddQuad(&scene, {p[4], p[7], p[6], p[5]}, wall);  // the ceiling
  AddQuad(&scene, {p[0], p[4], p[5], p[1]}, wall);
  AddQuad(&scene, {p[3], p[2], p[6], p[7]}, wall);
  AddQuad(&scene, {p[0], p[3], p[7], p[4]}, wall);
  AddQuad(&scene, {p[1], p[5], p[6], p[2]}, wall);
  AddBlock(&scene, {1.5, 1.5, 0}, {2.7, 2.3, 0.75}, table);
  AddBlock(&scene, {0, 3.2, 0}, {1.5, 4, 2}, cupboard);
  AddBlock(&scene, {2.6, 0, 0}, {4, 2, 0.5}, cupboard);  // the bed
  for (int k = 0; k < 8; ++k) {
    const double x = 0.6 + 0.9 * (k % 4), y = k < 4 ? 1.2 : 2.8;
    const double e = 6 * (k == 0 ? change.lamp0_scale : 1);
    const uint32_t lamp = AddMaterial(&scene, {}, {e, e, 0.9 * e});
    const double z = h - 0.01, s = 0.15;
    AddQuad(&scene,
            {Vec3{x - s, y - s, z}, Vec3{x - s, y + s, z}, Vec3{x + s, y + s, z},
             Vec3{x + s, y - s, z}},
            lamp);
  }
  return scene;
}

PatchReference TracePatchReference(const InputScene& input, const PatchScene& patches,
                                   uint32_t stride, double relative_error, unsigned threads) {
  PatchReference out;
  auto scene = reference::ReferenceScene::Build(input);
  if (!scene) return out;
  const reference::PathTracer tracer(**scene);
  reference::TraceSettings trace;
  trace.relative_error = relative_error;
  trace.min_samples = 2048;
  trace.threads = threads;
  std::vector<reference::SurfacePoint> points;
  for (uint32_t i = 0; i < patches.patches.size(); i += stride) {
    const Patch& p = patches.patches[i];
    if (p.emission.Max() > 0) continue;
    auto point = reference::LocatePoint(**scene, p.centre, p.normal);
    if (!point) continue;
    out.patches.push_back(i);
    points.push_back(*point);
  }
  const std::vector<reference::PointEstimate> estimates = tracer.EstimateAll(points, trace);
  std::vector<double> sums;
  for (const reference::PointEstimate& e : estimates) sums.push_back(e.radiance.Sum());
  std::nth_element(sums.begin(), sums.begin() + sums.size() / 2, sums.end());
  const double dark = sums.empty() ? 0 : 0.01 * sums[sums.size() / 2];
  // Points in the dark (the floor under a block) have no meaningful relative error: left out, as
  // the accuracy benchmark leaves them (docs/BENCHMARKS-accuracy.md).
  std::vector<uint32_t> lit;
  for (size_t k = 0; k < estimates.size(); ++k) {
    if (!(estimates[k].radiance.Sum() > dark)) continue;
    lit.push_back(out.patches[k]);
    out.radiance.push_back(estimates[k].radiance);
    out.relative_error.push_back(estimates[k].relative_error);
  }
  out.patches = std::move(lit);
  return out;
}

double RmsError(const std::vector<Rgb>& radiosity, const PatchReference& reference) {
  double sum = 0;
  for (size_t k = 0; k < reference.patches.size(); ++k) {
    const double e = radiosity[reference.patches[k]].Sum() / reference.radiance[k].Sum() - 1;
    sum += e * e;
  }
  return reference.patches.empty() ? 0 : std::sqrt(sum / double(reference.patches.size()));
}

}  // namespace radfarm::bench
