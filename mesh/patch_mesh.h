// PatchMesh: the scene split into radiosity patches, held in an OpenMesh polygon mesh (om_mesh.h)
// with a flat PatchScene copy for the solver, and its display topology (mesh/display_topology.h)
// for the display that follows the solve (display/).
//
// Build, in order (each step in its own file):
//   1. clean_faces.h     repeated and straight-through corners removed; zero-area faces dropped
//   2. hidden_faces.h    faces hidden inside a coplanar overlap dropped
//   3. surfaces.h        faces grouped into smooth surfaces (the units of vertex averaging)
//   4. polygon_split.h   each face split into patches no longer than its patch size on any edge
//      auto_patch_size.h the automatic size, per face, from the space the face looks into
//      contact_cut.h     patches cut along the footprints of solids standing on the face
//      narrow_space.h    pieces looking into a gap much narrower than they are split again
//   5. patch_assembler.h patches welded into the mesh; T-vertices between differently split faces
//                        of one surface found
// Tolerances scale with the bounding-box diagonal D of the faces: lengths 1e-6 D, areas 1e-12 D².
// Everything is deterministic: the same input gives the same patches in the same order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "core/rgb.h"
#include "input/input_scene.h"
#include "mesh/display_topology.h"
#include "mesh/mesh_settings.h"
#include "mesh/patch_assembler.h"

namespace radfarm {

// With MeshSettings::patch_size == 0 every face gets its own size from the space it looks into
// (mesh/auto_patch_size.h): about a tenth of a room's mean chord, 0.2 m in a 4 x 4 x 3 m office.
// Build refuses scenes that would need more patches than this (a patch size far too small).
inline constexpr uint64_t kMaxPatches = uint64_t{1} << 23;
// A sheet hanging within this many patch sizes of a face covers it (mesh/contact_cut.h): any gap
// a patch could straddle.
inline constexpr double kSheetReachPatches = 2;

// What Check finds out without building the mesh.
struct MeshCheck {
  uint64_t patches = 0;   // before welding: Build's count may differ a little
  double patch_size = 0;  // as PatchMesh::patch_size()
  double weld_tolerance = 0;
  uint64_t memory_limit = 0;  // as PatchMesh::memory_limit()
};

// Move-only: a copy of a large mesh is never wanted by accident.
class PatchMesh {
 public:
  // Splits every input polygon into patches no larger than the target size. Appends one-line
  // warnings (prefixed with scene.path) to *warnings (may be null) for dropped geometry. Errors: an
  // invalid patch size, an index out of range, no face left to mesh, too many patches.
  static Result<PatchMesh> Build(const InputScene& scene, const MeshSettings& settings,
                                 std::vector<std::string>* warnings);
  // Build's errors and warnings, all of them, and its patch count, without building: each face's
  // pieces are made, cut and probed for narrow spaces one face at a time and then dropped, so no
  // mesh is assembled (a small share of Build's memory at 10^5-10^6 patches, most of its
  // meshing time; `radfarm submit` checks a scene so before the master meshes it).
  static Result<MeshCheck> Check(const InputScene& scene, const MeshSettings& settings,
                                 std::vector<std::string>* warnings);

  // A mesh of the same scene made of these pieces instead (adaptive refinement, refine.h): same
  // materials, tolerances and patch size; welding and T-vertices found as by Build. Piece k becomes
  // patch k unless welding left it degenerate (then it is dropped: callers compare the counts).
  struct Piece {
    PieceCorners corners;
    uint32_t surface = 0;
    uint32_t material = 0;
  };
  // The T-vertex search runs on `pool` when given (the same mesh on any thread count).
  PatchMesh Rebuilt(const std::vector<Piece>& pieces, ThreadPool* pool = nullptr) const;
  // The pieces that rebuild a mesh with these patches: with Rebuilt, on the mesh Build made, this
  // recovers a refined mesh from its PatchScene alone (a farm checkpoint's scene blob).
  static std::vector<Piece> PiecesOf(const PatchScene& scene);
  // Welding distance of this mesh (1e-6 of the scene's diagonal).
  double weld_tolerance() const { return tol_; }
  // The memory the mesh was sized to hold in (MeshSettings::max_memory, or this machine's when
  // unset): refinement's automatic element budget stays within it too.
  uint64_t memory_limit() const { return memory_limit_; }

  // Flat copy the solver uses; patch i == OpenMesh face i.
  const PatchScene& patch_scene() const { return data_.scene; }
  // The flat copy alone, the rest of the mesh freed: for a solve that needs no display or
  // refinement (the OpenMesh mesh and its properties cost more than the flat copy).
  PatchScene TakePatchScene() && {
    PatchMesh dropped = std::move(*this);
    return std::move(dropped.data_.scene);
  }
  // Target size actually used: settings.patch_size, or when automatic (settings.patch_size == 0)
  // the median over the patches of their faces' sizes; the display's and refinement's lengths
  // (the display's gather band, min_element_size, the lightmap texel) follow it. Min and max are
  // the smallest and largest face sizes (equal to patch_size() unless automatic).
  double patch_size() const { return patch_size_; }
  double patch_size_min() const { return patch_size_min_; }
  double patch_size_max() const { return patch_size_max_; }
  size_t dropped_degenerate() const { return dropped_degenerate_; }
  size_t dropped_hidden() const { return dropped_hidden_; }
  size_t surface_count() const { return surface_count_; }
  // The surfaces under covering sheets (contact_cut.h): seen only through the slit under a sheet.
  const std::vector<uint32_t>& covered_surfaces() const { return covered_surfaces_; }
  // The user's objects (ObjectsOrDefault of the input scene), and the one each patch belongs to:
  // surfaces never span two objects (surfaces.h), so it is a function of the patch's surface, and
  // a refined mesh (Rebuilt, which keeps surfaces) knows it too.
  const std::vector<InputObject>& objects() const { return objects_; }
  // The input's faces with a lightmap UV (glTF TEXCOORD_1), for output/lightmap_writer.h.
  const std::vector<LightmapTriangle>& lightmap_triangles() const { return lightmap_triangles_; }
  // The faces of the objects without one (UnmappedTriangles), for output/lightmap_unwrap.h.
  const std::vector<LightmapTriangle>& unmapped_triangles() const { return unmapped_triangles_; }
  uint32_t patch_object(uint32_t patch) const {
    return surface_object_[data_.scene.patches[patch].surface];
  }

  // The display vertices, which patches touch them, and each patch's outline through them.
  DisplayTopology display_topology() const;

  // The OpenMesh mesh and its property handles, for inspection and tests.
  const OmMesh& mesh() const { return *data_.mesh; }
  const PatchProperties& properties() const { return data_.props; }

 private:
  PatchMesh() = default;

  PatchMeshData data_;
  double patch_size_ = 0;
  double patch_size_min_ = 0;
  double patch_size_max_ = 0;
  size_t dropped_degenerate_ = 0;
  size_t dropped_hidden_ = 0;
  size_t surface_count_ = 0;
  std::vector<uint32_t> covered_surfaces_;
  std::vector<InputObject> objects_;
  std::vector<uint32_t> surface_object_;  // by surface id
  std::vector<LightmapTriangle> lightmap_triangles_;
  std::vector<LightmapTriangle> unmapped_triangles_;
  std::vector<Material> materials_;
  double tol_ = 0;
  uint64_t memory_limit_ = 0;
  double min_area_ = 0;
};

}  // namespace radfarm
