// PatchAssembler: adds patch pieces to the OpenMesh mesh and the PatchScene in step, welding
// corners within tol, then finds the T-vertices. The result, PatchMeshData, is what PatchMesh
// keeps.
#pragma once

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/patch_scene.h"
#include "core/thread_pool.h"
#include "input/input_scene.h"
#include "mesh/om_mesh.h"
#include "mesh/point_grid.h"
#include "mesh/polygon_split.h"

namespace radfarm {

// A display vertex on the interior of a patch edge: a T-vertex, where a neighbouring patch of the
// same surface was gridded differently. Display triangles of the patch include it, and its value
// includes the patch, so shading is continuous across the edge.
struct EdgePoint {
  uint32_t face;
  uint32_t edge;  // from corner `edge` to corner `edge + 1`
  double t;       // position along the edge, in (0, 1)
  uint32_t group;
};

struct PatchMeshData {
  // Behind a pointer because OpenMesh meshes have no move constructor: every "move" would copy.
  std::unique_ptr<OmMesh> mesh = std::make_unique<OmMesh>();
  PatchProperties props;
  PatchScene scene;
  // Display vertices ("groups": one per surface and welded position), each with one OpenMesh vertex
  // standing for it. Several OpenMesh vertices share a group where a face could not be connected
  // without making the mesh non-manifold (it then gets vertices of its own).
  std::vector<OmMesh::VertexHandle> group_vertex;
  std::vector<EdgePoint> edge_points;  // sorted by face, edge, t
};

class PatchAssembler {
 public:
  // tol: welding distance; min_area: pieces smaller than this after welding are skipped.
  // expected_pieces: about how many pieces will be added (0: unknown). The mesh's arrays are
  // reserved for them, so they do not grow by copying (address space only: pages are touched as
  // they fill).
  PatchAssembler(double tol, double min_area, const std::vector<Material>& materials,
                 size_t expected_pieces = 0);

  // Adds one piece as the next patch. Returns false when welding left it degenerate.
  bool Add(const PieceCorners& piece, uint32_t surface, uint32_t material);

  // Finds the T-vertices (spread over `pool` when given) and hands the mesh over.
  PatchMeshData Finish(ThreadPool* pool = nullptr) &&;

 private:
  uint32_t GroupOf(uint32_t surface, uint32_t weld);
  uint32_t NewGroup(uint32_t surface, uint32_t weld);
  std::vector<OmMesh::VertexHandle> ConnectableVertices(const std::vector<uint32_t>& groups);
  void FindEdgePoints(ThreadPool* pool);

  double tol_;
  double min_area_;
  const std::vector<Material>& materials_;
  PointWelder welder_;
  // A weld's group on the first surface that used it, by weld id (kNoGroup: none yet); the
  // groups of the surfaces after it (the welds on surface borders) by surface << 32 | weld id.
  static constexpr uint32_t kNoGroup = UINT32_MAX;
  std::vector<uint32_t> first_group_of_weld_;
  std::unordered_map<uint64_t, uint32_t> other_group_of_key_;
  std::vector<uint32_t> group_surface_;
  double edge_length_sum_ = 0;
  PatchMeshData data_;
};

}  // namespace radfarm
