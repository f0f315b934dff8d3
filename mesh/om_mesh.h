// The OpenMesh mesh that holds the patches, and the properties stored on it. Face i is patch i of
// the PatchScene. Vertices are shared only within one surface (so a crease keeps one vertex per
// side); each vertex also records its display vertex ("group": one per surface and position).
#pragma once

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <array>
#include <cstdint>

#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm {

struct OmTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;  // doubles, like the rest of the core
  typedef OpenMesh::Vec3d Normal;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<OmTraits>;

inline OmMesh::Point ToOm(const Vec3& v) { return {v.x, v.y, v.z}; }
inline Vec3 FromOm(const OmMesh::Point& p) { return {p[0], p[1], p[2]}; }

// The corners of a face in patch order. PatchAssembler points each face's halfedge at the edge into
// corner 0, so walking `next` from it yields corners 0, 1, 2 (, 3). Returns the corner count.
inline int FaceCorners(const OmMesh& mesh, OmMesh::FaceHandle face,
                       std::array<OmMesh::VertexHandle, 4>* corners) {
  const OmMesh::HalfedgeHandle start = mesh.halfedge_handle(face);
  OmMesh::HalfedgeHandle h = start;
  int n = 0;
  do {
    (*corners)[n++] = mesh.to_vertex_handle(h);
    h = mesh.next_halfedge_handle(h);
  } while (h != start && n < 4);
  return n;
}

struct PatchProperties {
  OpenMesh::FPropHandleT<uint32_t> surface;
  OpenMesh::FPropHandleT<uint32_t> material;
  OpenMesh::FPropHandleT<Rgb> reflectance;
  OpenMesh::FPropHandleT<Rgb> emission;
  OpenMesh::FPropHandleT<double> area;
  OpenMesh::FPropHandleT<Vec3> normal;
  OpenMesh::VPropHandleT<uint32_t> group;

  // Property handles are indices, so they stay valid in copies and moves of the mesh.
  void AddTo(OmMesh* mesh) {
    mesh->add_property(surface, "surface");
    mesh->add_property(material, "material");
    mesh->add_property(reflectance, "reflectance");
    mesh->add_property(emission, "emission");
    mesh->add_property(area, "area");
    mesh->add_property(normal, "normal");
    mesh->add_property(group, "group");
  }
};

}  // namespace radfarm
