// PatchMesh's second half: from patch radiosities to vertex radiance and display triangles.
#include <cstdio>
#include <cstdlib>

#include "mesh/border_extrapolation.h"
#include "mesh/ear_clip.h"
#include "mesh/patch_mesh.h"
#include "mesh/polygon.h"

namespace radfarm {

void PatchMesh::SetSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot) {
  OmMesh& mesh = *data_.mesh;
  const PatchProperties& p = data_.props;
  const size_t faces = data_.scene.patches.size();
  if (radiosity.size() != faces || unshot.size() != faces) {
    std::fprintf(stderr,
                 "PatchMesh::SetSolution: %zu radiosities, %zu unshot values, %zu patches\n",
                 radiosity.size(), unshot.size(), faces);
    std::abort();
  }
  std::vector<Rgb> sum(data_.group_vertex.size());
  std::vector<double> weight(data_.group_vertex.size(), 0.0);
  auto accumulate = [&](uint32_t group, uint32_t face) {
    const double area = data_.scene.patches[face].area;
    sum[group] += radiosity[face] * area;
    weight[group] += area;
  };
  for (uint32_t f = 0; f < faces; ++f) {
    const OmMesh::FaceHandle fh = mesh.face_handle(f);
    mesh.property(p.radiosity, fh) = radiosity[f];
    mesh.property(p.unshot, fh) = unshot[f];
    for (OmMesh::VertexHandle vh : mesh.fv_range(fh)) accumulate(mesh.property(p.group, vh), f);
  }
  for (const EdgePoint& e : data_.edge_points) accumulate(e.group, e.face);
  std::vector<Rgb> value(sum.size());
  for (size_t g = 0; g < sum.size(); ++g) value[g] = weight[g] > 0 ? sum[g] / weight[g] : Rgb();
  ExtrapolateBorders(FaceRings(), &value);
  for (OmMesh::VertexHandle vh : mesh.vertices()) {
    mesh.property(p.radiance, vh) = value[mesh.property(p.group, vh)];
  }
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
