// PatchMesh's display topology: the OpenMesh mesh read out as plain data for display/.
#include <array>

#include "mesh/patch_mesh.h"

namespace radfarm {

DisplayTopology PatchMesh::display_topology() const {
  const OmMesh& mesh = *data_.mesh;
  const PatchProperties& p = data_.props;
  const size_t patches = data_.scene.patches.size();
  DisplayTopology out;
  out.positions.reserve(data_.group_vertex.size());
  for (OmMesh::VertexHandle vh : data_.group_vertex)
    out.positions.push_back(FromOm(mesh.point(vh)));
  out.corner_begin.reserve(patches + 1);
  out.corner_begin.push_back(0);
  for (uint32_t f = 0; f < patches; ++f) {
    for (OmMesh::VertexHandle vh : mesh.fv_range(mesh.face_handle(f))) {
      out.corner_vertex.push_back(mesh.property(p.group, vh));
      out.corner_position.push_back(FromOm(mesh.point(vh)));
    }
    out.corner_begin.push_back(static_cast<uint32_t>(out.corner_vertex.size()));
  }
  out.edge_vertices.reserve(data_.edge_points.size());
  for (const EdgePoint& e : data_.edge_points) out.edge_vertices.push_back({e.face, e.group});
  out.rings.resize(patches);
  auto edge_point = data_.edge_points.begin();
  for (uint32_t f = 0; f < patches; ++f) {
    std::array<OmMesh::VertexHandle, 4> corners;
    const int n = FaceCorners(mesh, mesh.face_handle(f), &corners);
    for (int j = 0; j < n; ++j) {
      out.rings[f].push_back(mesh.property(p.group, corners[j]));
      for (; edge_point != data_.edge_points.end() && edge_point->face == f &&
             edge_point->edge == static_cast<uint32_t>(j);
           ++edge_point) {
        out.rings[f].push_back(edge_point->group);
      }
    }
  }
  return out;
}

}  // namespace radfarm
