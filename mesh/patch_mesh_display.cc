// PatchMesh's second half: from patch radiosities to vertex radiance and display triangles.
#include <array>
#include <cstdio>
#include <cstdlib>

#include "core/direct_light.h"
#include "mesh/border_extrapolation.h"
#include "mesh/ear_clip.h"
#include "mesh/gouraud_means.h"
#include "mesh/patch_mesh.h"
#include "mesh/polygon.h"

namespace radfarm {

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
  StoreSolution(radiosity, unshot);
  std::vector<Rgb> value = VertexAverages(radiosity);
  ExtrapolateBorders(FaceRings(), &value);
  SetVertexRadiance(value);
}

void PatchMesh::SetSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot,
                            const VertexDirectLight& direct) {
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
  std::vector<Rgb> value = VertexAverages(rest);
  ExtrapolateBorders(FaceRings(), &value);
  const std::vector<Rgb> rho = VertexAverages(reflectance);

  // Each vertex's point: a hair inside the patches around it (toward their centres), so a vertex
  // on a crease or at the foot of a wall sees the light as the surface beside it does.
  const size_t groups = data_.group_vertex.size();
  std::vector<Vec3> centre_sum(groups), normal_sum(groups);
  std::vector<uint32_t> count(groups, 0);
  ForEachVertexPatch([&](uint32_t group, uint32_t face) {
    centre_sum[group] = centre_sum[group] + patches[face].centre;
    normal_sum[group] = normal_sum[group] + patches[face].normal * patches[face].area;
    ++count[group];
  });
  std::vector<ReceiverPoint> points;
  std::vector<uint32_t> point_group;
  for (uint32_t g = 0; g < groups; ++g) {
    const double length = Length(normal_sum[g]);
    if (count[g] == 0 || !(length > 0)) continue;
    const Vec3 at = FromOm(data_.mesh->point(data_.group_vertex[g]));
    const Vec3 inward = centre_sum[g] / double(count[g]) - at;
    points.push_back({at + inward * kVertexInset, normal_sum[g] / length});
    point_group.push_back(g);
  }
  // Then each patch's centre (after the vertices, so their shadow rays keep their keys).
  const size_t vertex_points = points.size();
  for (const Patch& p : patches) points.push_back({p.centre, p.normal});
  const std::vector<Rgb> irradiance =
      PointsDirectLight(data_.scene, points, direct.seed, direct.threads);
  std::vector<Rgb> vertex_irradiance(groups);
  for (size_t k = 0; k < vertex_points; ++k) {
    const uint32_t g = point_group[k];
    vertex_irradiance[g] = irradiance[k];
    value[g] += rho[g] * irradiance[k];
  }
  SetVertexRadiance(value);

  // Point values interpolated linearly run below the light wherever it is concave (the peak under
  // a lamp, the fall-off down a wall) and above it where it is convex: on every patch, by about
  // h^2 f'' / 12. So each vertex then moves by the average over its patches of what the patch's
  // Gouraud mean misses of the patch's mean light: the rest as solved plus rho times the direct
  // light's mean from its corners and centre, by the rule exact for quadratics (a parallelogram:
  // (corner mean + 2 centre) / 3; a triangle: (corner mean + 3 centre) / 4).
  const OmMesh& om = *data_.mesh;
  std::vector<Rgb> target(patches.size());
  for (uint32_t f = 0; f < patches.size(); ++f) {
    std::array<OmMesh::VertexHandle, 4> corners;
    const int n = FaceCorners(om, om.face_handle(static_cast<int>(f)), &corners);
    Rgb corner_mean;
    for (int k = 0; k < n; ++k) {
      corner_mean += vertex_irradiance[om.property(data_.props.group, corners[k])];
    }
    corner_mean = corner_mean / double(n);
    const Rgb& centre = irradiance[vertex_points + f];
    const Rgb mean = n == 4 ? (corner_mean + centre * 2) / 3 : (corner_mean + centre * 3) / 4;
    target[f] = rest[f] + patches[f].reflectance * mean;
  }
  // One step only: more steps match the means closer, yet the unit scene's image error grew.
  const std::vector<Rgb> shown = GouraudPatchMeans(MakeDisplayMesh(), patches.size());
  std::vector<Rgb> shortfall(patches.size());
  for (size_t f = 0; f < patches.size(); ++f) {
    if (patches[f].emission.Max() == 0) shortfall[f] = target[f] - shown[f];
  }
  const std::vector<Rgb> correction = VertexAverages(shortfall);
  for (size_t g = 0; g < value.size(); ++g) value[g] += correction[g];
  SetVertexRadiance(value);
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
  const OmMesh& mesh = *data_.mesh;
  const PatchProperties& p = data_.props;
  DisplayMesh out;
  for (OmMesh::VertexHandle vh : data_.group_vertex) {
    out.positions.push_back(FromOm(mesh.point(vh)));
    out.radiance.push_back(mesh.property(p.radiance, vh));
  }
  const std::vector<std::vector<uint32_t>> rings = FaceRings();
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
