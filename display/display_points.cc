#include "display/display_points.h"

#include "display/display_settings.h"
#include "mesh/vertex_averages.h"

namespace radfarm {
namespace {

// Emitters show their emission: their points keep the average.
bool KeepsAverage(const Patch& p) { return p.emission.Max() > 0; }

// The display vertices' points.
void PlaceVertexPoints(const DisplayTopology& topology, const PatchScene& scene,
                       DisplayPoints* out) {
  const std::vector<Patch>& patches = scene.patches;
  const size_t vertices = topology.vertex_count();
  std::vector<Vec3> centre_sum(vertices), normal_sum(vertices);
  std::vector<uint32_t> count(vertices, 0);
  std::vector<bool> average(vertices, false);
  topology.ForEachVertexPatch([&](uint32_t vertex, uint32_t face) {
    centre_sum[vertex] = centre_sum[vertex] + patches[face].centre;
    normal_sum[vertex] = normal_sum[vertex] + patches[face].normal * patches[face].area;
    average[vertex] = average[vertex] || KeepsAverage(patches[face]);
    ++count[vertex];
  });
  out->point_of.assign(vertices, kNoDisplayPoint);
  for (uint32_t v = 0; v < vertices; ++v) {
    const double length = Length(normal_sum[v]);
    if (count[v] == 0 || !(length > 0)) continue;
    const Vec3& at = topology.positions[v];
    const Vec3 inward = centre_sum[v] / double(count[v]) - at;
    out->point_of[v] = static_cast<uint32_t>(out->points.size());
    out->points.push_back({at + inward * kVertexInset, normal_sum[v] / length});
    out->may_gather.push_back(!average[v]);
  }
  std::vector<Rgb> reflectance(patches.size());
  for (size_t f = 0; f < patches.size(); ++f) reflectance[f] = patches[f].reflectance;
  out->rho = VertexAverages(topology, scene, reflectance);
}

// The midpoints' points: a hair toward the centroids of the triangles beside each edge.
void PlaceMidpointPoints(const PatchScene& scene, const MidpointSplit& split, DisplayPoints* out) {
  const std::vector<Patch>& patches = scene.patches;
  const DisplayMesh& fine = split.mesh;
  const size_t midpoints = split.edge_ends.size();
  std::vector<Vec3> centroids(midpoints), normals(midpoints);
  std::vector<Rgb> rho(midpoints);
  std::vector<double> weight(midpoints, 0.0);
  std::vector<bool> average(midpoints, false);
  std::vector<uint32_t> triangles(midpoints, 0);
  for (size_t t = 0; t < split.triangle_midpoints.size(); ++t) {
    const std::array<uint32_t, 3>& v = fine.triangles[4 * t + 3];  // the middle triangle
    const Vec3 centroid =
        (fine.positions[v[0]] + fine.positions[v[1]] + fine.positions[v[2]]) / 3.0;
    const Patch& p = patches[fine.triangle_patch[4 * t]];
    for (uint32_t m : split.triangle_midpoints[t]) {
      const uint32_t k = m - split.coarse_vertices;
      centroids[k] = centroids[k] + centroid;
      normals[k] = normals[k] + p.normal * p.area;
      rho[k] += p.reflectance * p.area;
      weight[k] += p.area;
      average[k] = average[k] || KeepsAverage(p);
      ++triangles[k];
    }
  }
  const size_t vertices = split.coarse_vertices;
  out->rho.resize(vertices + midpoints);
  out->point_of.resize(vertices + midpoints, kNoDisplayPoint);
  for (size_t k = 0; k < midpoints; ++k) {
    const double length = Length(normals[k]);
    if (!(length > 0) || !(weight[k] > 0)) continue;
    const Vec3& at = fine.positions[vertices + k];
    const Vec3 inward = centroids[k] / double(triangles[k]) - at;
    out->rho[vertices + k] = rho[k] / weight[k];
    out->point_of[vertices + k] = static_cast<uint32_t>(out->points.size());
    out->points.push_back({at + inward * kVertexInset, normals[k] / length});
    out->may_gather.push_back(!average[k]);
  }
}

}  // namespace

DisplayPoints PlaceDisplayPoints(const DisplayTopology& topology, const PatchScene& scene,
                                 const MidpointSplit& split) {
  DisplayPoints out;
  PlaceVertexPoints(topology, scene, &out);
  PlaceMidpointPoints(scene, split, &out);
  return out;
}

}  // namespace radfarm
