// PatchMesh: the scene split into radiosity patches, held in an OpenMesh polygon mesh (om_mesh.h)
// with a flat PatchScene copy for the solver; after the solve it turns patch radiosities into
// per-vertex radiance for display.
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
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "core/point_gather.h"
#include "core/rgb.h"
#include "input/input_scene.h"
#include "mesh/display_mesh.h"
#include "mesh/mesh_settings.h"
#include "mesh/patch_assembler.h"

namespace radfarm {

// With MeshSettings::patch_size == 0 every face gets its own size from the space it looks into
// (mesh/auto_patch_size.h): about a tenth of a room's mean chord, 0.2 m in a 4 x 4 x 3 m office.
// Build refuses scenes that would need more patches than this (a patch size far too small).
inline constexpr uint64_t kMaxPatches = uint64_t{1} << 23;
// How far toward the centres of its patches a vertex's direct light is computed, as a share of
// the distance: far enough off a crease for its shadow rays, near enough to be the vertex's value.
inline constexpr double kVertexInset = 1e-4;
// A sheet hanging within this many patch sizes of a face covers it (mesh/contact_cut.h): any gap
// a patch could straddle.
inline constexpr double kSheetReachPatches = 2;
// A display point gathers its bounced light itself (core/point_gather.h) when a surface lies
// within this many patch sizes.
inline constexpr double kGatherBand = 1.5;

// What Check finds out without building the mesh.
struct MeshCheck {
  uint64_t patches = 0;   // before welding: Build's count may differ a little
  double patch_size = 0;  // as PatchMesh::patch_size()
  double weld_tolerance = 0;
  uint64_t memory_limit = 0;  // as PatchMesh::memory_limit()
};

// How many times the display cuts its triangles where the light bends (patch_mesh_display.cc).
inline constexpr int kDisplayRefineLevels = 3;

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
  // refinement (the OpenMesh mesh and its properties are about 300 bytes a patch).
  PatchScene TakePatchScene() && {
    PatchMesh dropped = std::move(*this);
    return std::move(dropped.data_.scene);
  }
  // Target size actually used: settings.patch_size, or when automatic (settings.patch_size == 0)
  // the median over the patches of their faces' sizes; the display's and refinement's lengths
  // (kGatherBand, min_element_size, the lightmap texel) follow it. Min and max are the smallest
  // and largest face sizes (equal to patch_size() unless automatic).
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
  uint32_t patch_object(uint32_t patch) const {
    return surface_object_[data_.scene.patches[patch].surface];
  }

  // Stores the solution (one value per patch, in the solver's units: those of the emission) in the
  // face properties B and dB, and sets each vertex's radiance to the area-weighted average of B
  // over the patches of its surface that touch it: as a corner, or with the vertex on an edge (a
  // T-vertex). Values never mix across surfaces, so creases stay sharp. Vertices on a surface's
  // border are then extrapolated from the inside (mesh/border_extrapolation.h).
  void SetSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot);

  // A step of SetSolution's display as it starts: the direct light at its points, gathering at
  // those near other surfaces, or a level of cutting where the light bends.
  struct DisplayStep {
    enum Kind { kDirectLight, kGathering, kRefining } kind = kDirectLight;
    uint64_t points = 0;  // the direct light's and gathering's points, or those a level adds
    int level = 0;        // kRefining: 1 to kDisplayRefineLevels
  };
  // The direct light a solve started from (SolveResult::direct_light, one value per patch), and
  // the keys and threads for the vertices' own shadow rays.
  struct VertexDirectLight {
    const std::vector<Rgb>& patch_direct;
    uint64_t seed = 0;
    unsigned threads = 0;  // 0: all cores
    // Whether patch_direct holds the emitter patches' light (EmittersInDirectStart) or only the
    // punctual lights' (the emitters shot theirs): the points then compute the same.
    bool emitters = true;
    // Shadow rays per light at a point at most (DirectLightRaysPerLight, as the start; 0: no
    // limit).
    uint32_t rays_per_light = 0;
    // The rays the display may cast (DisplayRayAllowance: a share of the job's budget; 0: no
    // limit). Within it, in this order and only as far as needed: fewer shadow rays per light
    // (down to kMinCappedLightRays), fewer gathering rays (down to kMinDisplayGatherRays, else no
    // point gathers), fewer levels of cutting where the light bends; where even the fewest shadow
    // rays at every point would exceed it, the display averages the patches (no ray).
    uint64_t ray_allowance = 0;
  };
  // As above, but the display is finer than the solution and shows the direct light where it is
  // computed. Every display triangle is cut into four at its edge midpoints (midpoint_split.h), and
  // every display point, vertex or midpoint, shows rho times DirectLight at the point itself
  // (core/direct_light.h) plus the rest of the solution (radiosity less rho times the patch's
  // direct light: emission and bounced light, which is smooth) averaged over the patches around
  // it, linearly between a midpoint's two ends. Averages put a vertex at the mean of its patches:
  // where the direct light bends (the fall-off near a light, a penumbra) that is not its value
  // there, and the Gouraud image would show every patch's outline; the direct light at the point
  // is exact outside shadows. Then one step (StepTowardPatchMeans) moves every point by its
  // patches' shortfall of Gouraud mean against mean light (the rest as solved plus rho times the
  // direct light's mean over the patch by the midpoint rule, exact for quadratics): point values
  // interpolated linearly run below a concave light between points (h^2 f'' / 12 on every
  // triangle). Costs a point of shadow rays (kPointShadowRays) per display vertex and midpoint.
  // Near another surface (within kGatherBand patch sizes: corners, the ceiling beside a hanging
  // lamp, the floor around a block) the rest is not smooth across a patch: such points gather it
  // themselves (core/point_gather.h) and keep their values. Where the corners of a triangle of
  // such points differ by more than a fifth (a tenth for a sliver), or the direct light at the
  // corners of any other does (a hard shadow's edge), it is cut (mesh/display_cut.h,
  // mesh/selective_split.h) and its new points computed the same way, up to three levels deep
  // (patch_mesh_display.cc).
  // `progress`, when set, is told on the calling thread as each step of the display starts (a big
  // scene's display can take longer than its solve): what it does, at how many points.
  using DisplayProgress = std::function<void(const DisplayStep&)>;
  void SetSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot,
                   const VertexDirectLight& direct, const DisplayProgress& progress = nullptr);
  // What the last SetSolution with VertexDirectLight computed: display points (vertices and
  // midpoints), those that gathered their own light near another surface, and those added where
  // the light bends; and its wall time.
  // And the rays it cast and what it spent them on.
  struct DisplayStats {
    uint64_t points = 0;
    uint64_t gathered = 0;
    uint64_t added = 0;
    double seconds = 0;
    uint64_t rays = 0;            // shadow and gathering rays, second bounces and probes included
    uint32_t rays_per_light = 0;  // as VertexDirectLight's, or fewer under an allowance
    uint32_t gather_rays = 0;     // per gathering point (0: none gathered)
    int levels = 0;               // of cutting where the light bends, at most kDisplayRefineLevels
    bool averaged = false;        // the allowance did not cover one point's direct light: averages
  };
  const DisplayStats& display_stats() const { return display_stats_; }

  // Triangles with per-vertex radiance for the image and the PLY: one vertex per surface and
  // position, patches with T-vertices on their edges triangulated through them, so Gouraud shading
  // is continuous within a surface; after SetSolution with VertexDirectLight, those triangles cut
  // at their midpoints. Radiance is zero before SetSolution.
  DisplayMesh MakeDisplayMesh() const;

  // The OpenMesh mesh and its property handles, for inspection and tests.
  const OmMesh& mesh() const { return *data_.mesh; }
  const PatchProperties& properties() const { return data_.props; }

 private:
  PatchMesh() = default;
  // Per patch, its display vertices in order: corners and the T-vertices on its edges.
  std::vector<std::vector<uint32_t>> FaceRings() const;
  // The solution into the face properties B and dB (aborts on a size mismatch).
  void StoreSolution(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& unshot);
  // visit(display vertex, patch) for every patch touching a display vertex (corner or T-vertex).
  template <typename Visit>
  void ForEachVertexPatch(Visit&& visit) const;
  // Per display vertex, the area-weighted average of a per-patch value over its patches.
  std::vector<Rgb> VertexAverages(const std::vector<Rgb>& per_patch) const;
  // Per patch corner, the direct light it reflects there (rho times `irradiance` at the corner's
  // display vertex, whose point is point_of[vertex]) less the patch's mean (rho times
  // patch_direct): what gathering rays add where they meet the patch (core/point_gather.h).
  PatchCornerOffsets CornerDirectOffsets(const std::vector<Rgb>& irradiance,
                                         const std::vector<uint32_t>& point_of,
                                         const std::vector<Rgb>& patch_direct) const;
  void SetVertexRadiance(const std::vector<Rgb>& value);
  // The display triangles of the patches, at the vertices' radiance.
  DisplayMesh PatchDisplayMesh() const;

  PatchMeshData data_;
  // The display cut at its midpoints by SetSolution with VertexDirectLight; empty otherwise.
  std::optional<DisplayMesh> split_display_;
  DisplayStats display_stats_;
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
  std::vector<Material> materials_;
  double tol_ = 0;
  uint64_t memory_limit_ = 0;
  double min_area_ = 0;
};

}  // namespace radfarm
