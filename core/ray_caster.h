// RayCaster: closest-hit queries against one Embree BVH of all patches.
//
// Precision: Embree works in single precision, so the scene is translated to be centred on the
// origin (in double) before it is handed to Embree; a room far from the origin then traces exactly
// like the same room at the origin. The BVH is built in robust (watertight) mode so that rays do
// not slip between triangles that share an edge.
//
// Two-sided surfaces (Patch::two_sided) are two patches back to back at the same place. They go
// into a second Embree geometry whose filter drops hits on a patch's back, so a ray meets the side
// that faces it, whichever of the two Embree finds first; a scene without them has the one
// geometry and traces exactly as before. Shadow rays (Unoccluded) take any hit.
//
// Memory: Embree's robust BVH keeps its own copy of every triangle's corners in its leaves, so the
// float vertices and indices handed to it are freed once it is built. What stays is the BVH, 8
// bytes a triangle of records, and the normals.
//
// Thread safety: Trace() is const and may be called from any number of threads at once.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "core/patch_scene.h"
#include "core/ray_sampler.h"
#include "core/vec3.h"

struct RTCSceneTy;                   // Embree's scene handle type (embree3/rtcore_scene.h)
struct RTCRayHit;                    // Embree's ray and hit record (embree3/rtcore_ray.h)
struct RTCFilterFunctionNArguments;  // a filter callback's arguments (embree3/rtcore_geometry.h)

namespace radfarm {

struct RayHit {
  static constexpr uint32_t kMiss = 0xffffffffu;
  uint32_t patch = kMiss;  // patch id, or kMiss when the ray left the scene
  bool front = true;       // false when the ray hit the back of the patch
};

class RayCaster {
 public:
  // Builds the BVH (a copy: the scene need not outlive the caster).
  explicit RayCaster(const PatchScene& scene);
  // The same caster from the patches' shapes and whether each is two-sided (Patch::two_sided):
  // what an agent keeps of a scene (agent/prepared_scene.h). `shapes` must outlive the caster,
  // which reads their normals instead of copying them.
  RayCaster(std::span<const PatchShape> shapes, std::span<const uint8_t> two_sided);
  // `patches(each)` calls each(shape, two_sided) for every patch, in id order.
  using PatchVisitor = std::function<void(const PatchShape& shape, bool two_sided)>;
  using PatchStream = std::function<void(const PatchVisitor& each)>;
  // The same caster from a stream of `count` patches, read twice (bounds and counts, then Embree's
  // buffers) and not kept: an agent builds it before it decodes the shapes it keeps, so the
  // build's scratch never sits on top of them (agent/prepared_scene.h). Tracing reads patch i's
  // normal at byte offset i * normal_stride from `normals`, which must hold them (bit for bit the
  // shapes' normals) before the first trace and outlive the caster; they need not exist yet.
  RayCaster(size_t count, const PatchStream& patches, const Vec3* normals, size_t normal_stride);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Closest hit along origin + t * direction for t > 0; origin in scene coordinates. The origin is
  // lifted off its surface by a small scene-relative offset along `surface_normal` so the ray does
  // not hit the surface it starts on.
  RayHit Trace(const Vec3& origin, const Vec3& direction, const Vec3& surface_normal) const;

  // Trace for each ray of `block` (all leaving a surface with `surface_normal`): hits[i] is bit
  // for bit Trace(origin i, direction i, surface_normal). The rays are traced 16 at a time as
  // Embree packets (rtcIntersect16, a little faster than one by one on these incoherent rays
  // with AVX-512), the last fewer than 16 one by one; each hit's triangle record is fetched while
  // the next rays trace, and the hits' patches and sides are worked out after them, so the cache
  // misses overlap instead of following each trace.
  // A hit's side comes from Embree's Ng where its sign is certain to be that of the patch normal's
  // (Triangle::ng_margin), otherwise from the patch normal as in Trace.
  void TraceBlock(const RayBlock& block, const Vec3& surface_normal, RayHit* hits) const;
  // The same for a block of rays of several shooters: ray i leaves the surface with normal
  // surface_normals[i].
  void TraceBlock(const RayBlock& block, const Vec3* surface_normals, RayHit* hits) const;

  // Whether nothing lies between origin (lifted as by Trace) and `target`: a shadow ray. It stops
  // kShadowRayMargin of the way short of the target, so the surface the target lies on does not
  // count as an occluder. Cheaper than Trace: any hit ends the search.
  bool Unoccluded(const Vec3& origin, const Vec3& target, const Vec3& surface_normal) const;
  static constexpr double kShadowRayMargin = 1e-4;
  // Unoccluded for shadow rays from one origin to each of `count` targets: unoccluded[i] is
  // Unoccluded(origin, targets[i], surface_normal). Traced 16 at a time as Embree packets
  // (rtcOccluded16): a point's shadow rays toward one light run nearly parallel and share most of
  // their BVH nodes. The last fewer than 16 go one by one.
  void UnoccludedBlock(const Vec3& origin, const Vec3& surface_normal, const Vec3* targets,
                       int count, bool* unoccluded) const;

  // The origin offset used by Trace, in scene units (useful for tests and diagnostics).
  double origin_offset() const { return origin_offset_; }

  // For benchmarks that time raw Embree calls on the same BVH: the committed scene (its coordinates
  // are scene coordinates minus the scene's centre; PrepareRay converts); primitive k belongs to
  // patch PatchOfTriangle(k).
  RTCSceneTy* embree_scene() const;
  // Fills `ray` exactly as Trace() would before calling Embree (origin moved to Embree's frame and
  // lifted off its surface, no hit yet).
  void PrepareRay(const Vec3& origin, const Vec3& direction, const Vec3& surface_normal,
                  RTCRayHit* ray) const;
  uint32_t PatchOfTriangle(uint32_t primitive) const { return triangles_[primitive].patch; }
  // The patch of Embree's (geometry, primitive), for queries on embree_scene() (point queries).
  uint32_t PatchOf(unsigned geometry, unsigned primitive) const {
    return TriangleOf(geometry, primitive).patch;
  }
  // What embree_scene()'s coordinates are relative to: scene = Embree + centre().
  const Vec3& centre() const { return centre_; }
  // Embree's geometry ids: one-sided patches, and the sides of two-sided surfaces (filtered).
  static constexpr unsigned kOneSidedGeometry = 0;
  static constexpr unsigned kTwoSidedGeometry = 1;

 private:
  // What a hit on one of Embree's triangles needs: its patch, and how far the direction of the
  // triangle's normal as Embree reports it (Ng) may be from its patch's normal, in cosine, float
  // rounding included: TraceBlock takes a hit's side from Ng when the ray's cosine with Ng is
  // further from 0 than this, so it need not read the patch's normal.
  struct Triangle {
    uint32_t patch;
    float ng_margin;  // +inf: always read the patch's normal
  };
  static float NgMargin(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& patch_normal,
                        double scene_diagonal);
  // TraceBlock for rays lifted off their surfaces by lift_of(i) (the normal times origin_offset_).
  template <typename LiftOf>
  void TraceLifted(const RayBlock& block, const LiftOf& lift_of, RayHit* hits) const;
  // Rays TraceBlock gives Embree at once (rtcIntersect16).
  static constexpr int kPacket = 16;
  // TraceBlock's hit of ray i of `block` on Embree's (geometry, primitive) with normal ng.
  RayHit HitOf(const RayBlock& block, int i, unsigned geometry, unsigned primitive,
               const Vec3& ng) const;
  // Whether direction d meets the front of `triangle`, given Embree's Ng for the hit: TraceBlock's
  // rule, which the two-sided filter applies too.
  bool MeetsFront(const Triangle& triangle, const Vec3& d, const Vec3& ng) const;
  // The triangle record of Embree's (geometry, primitive).
  const Triangle& TriangleOf(unsigned geometry, unsigned primitive) const {
    return triangles_[(geometry == kTwoSidedGeometry ? two_sided_first_ : 0) + primitive];
  }
  // Embree's intersection filter on the two-sided geometry: drops hits on a patch's back.
  static void FrontOnlyFilter(const RTCFilterFunctionNArguments* args);

  void Build(size_t count, const PatchStream& patches);

  struct Embree;
  std::unique_ptr<Embree> embree_;
  // A patch's normal: a compact copy (Trace reads one per hit), or the borrowed shapes'.
  const Vec3& NormalOf(uint32_t patch) const {
    return *reinterpret_cast<const Vec3*>(normals_ + patch * normal_stride_);
  }
  std::vector<Vec3> patch_normals_;  // from a PatchScene only
  const char* normals_ = nullptr;
  size_t normal_stride_ = sizeof(Vec3);
  std::vector<Triangle> triangles_;  // one-sided by primitive id, then two-sided; 8 bytes each
  size_t two_sided_first_ = 0;       // index in triangles_ of the two-sided geometry's first
  Vec3 centre_;                      // subtracted from every coordinate given to Embree
  double origin_offset_ = 0;
};

}  // namespace radfarm
