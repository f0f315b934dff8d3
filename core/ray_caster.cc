#include "core/ray_caster.h"

#include <embree3/rtcore.h>
#include <malloc.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <string>

#include "core/embree_handles.h"

namespace radfarm {

struct RayCaster::Embree : EmbreeHandles {};

namespace {

// An Embree record for a closest-hit query from `o` (relative to the scene centre) along `d`.
inline void SetRay(float ox, float oy, float oz, float dx, float dy, float dz, RTCRayHit* ray) {
  RTCRayHit& rh = *ray;
  rh.ray.org_x = ox;
  rh.ray.org_y = oy;
  rh.ray.org_z = oz;
  rh.ray.dir_x = dx;
  rh.ray.dir_y = dy;
  rh.ray.dir_z = dz;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = INFINITY;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
}

// A geometry's float corners and index triplets, from the heap (which reuses what earlier stages
// freed) and handed back once the BVH is built, its free pages returned to the system.
struct GeometryBuffers {
  float* vertices = nullptr;
  unsigned* indices = nullptr;

  GeometryBuffers() = default;
  GeometryBuffers(const GeometryBuffers&) = delete;
  GeometryBuffers& operator=(const GeometryBuffers&) = delete;
  ~GeometryBuffers() { Release(); }
  void Allocate(size_t triangle_count, size_t vertex_count) {
    // +1 vertex: Embree may read 16 bytes past the last float3.
    vertices = static_cast<float*>(std::malloc((vertex_count + 1) * 3 * sizeof(float)));
    indices = static_cast<unsigned*>(std::malloc(triangle_count * 3 * sizeof(unsigned)));
    if (!vertices || !indices) throw std::bad_alloc();
  }
  void Release() {
    std::free(vertices);
    std::free(indices);
    vertices = nullptr;
    indices = nullptr;
  }
};

}  // namespace

RayCaster::RayCaster(const PatchScene& scene) : embree_(std::make_unique<Embree>()) {
  // A compact copy of the normals: Trace reads one per hit, and a Patch is 224 bytes.
  patch_normals_.reserve(scene.patches.size());
  for (const Patch& p : scene.patches) patch_normals_.push_back(p.normal);
  normals_ = reinterpret_cast<const char*>(patch_normals_.data());
  Build(scene.patches.size(), [&scene](const PatchVisitor& each) {
    for (const Patch& p : scene.patches) each(p, p.two_sided);
  });
}

RayCaster::RayCaster(std::span<const PatchShape> shapes, std::span<const uint8_t> two_sided)
    : embree_(std::make_unique<Embree>()) {
  if (two_sided.size() != shapes.size()) {
    throw std::invalid_argument("RayCaster: one two-sided flag per shape needed");
  }
  normals_ = reinterpret_cast<const char*>(&shapes.data()->normal);
  normal_stride_ = sizeof(PatchShape);
  Build(shapes.size(), [&](const PatchVisitor& each) {
    for (size_t i = 0; i < shapes.size(); ++i) each(shapes[i], two_sided[i] != 0);
  });
}

RayCaster::RayCaster(size_t count, const PatchStream& patches, const Vec3* normals,
                     size_t normal_stride)
    : embree_(std::make_unique<Embree>()),
      normals_(reinterpret_cast<const char*>(normals)),
      normal_stride_(normal_stride) {
  Build(count, patches);
}

void RayCaster::Build(size_t count, const PatchStream& patches) {
  // First pass: the bounds, and each geometry's triangles and corners.
  Bounds3 bounds;
  size_t triangle_count[2] = {0, 0}, vertex_count[2] = {0, 0};
  size_t seen = 0;
  patches([&](const PatchShape& p, bool two_sided) {
    for (int k = 0; k < p.corner_count; ++k) bounds.Extend(p.corners[k]);
    triangle_count[two_sided] += p.corner_count - 2;
    vertex_count[two_sided] += p.corner_count;
    ++seen;
  });
  if (seen != count) throw std::invalid_argument("RayCaster: the stream has the wrong count");
  centre_ = bounds.Empty() ? Vec3{} : bounds.Centre();
  // A few thousand float ulps at the scene's scale: far above rounding, far below any feature.
  origin_offset_ = std::max(bounds.Diagonal(), 1e-30) * 1e-6;
  const double diagonal = bounds.Diagonal();

  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) throw std::runtime_error("cannot create an Embree device");
  embree_->scene = rtcNewScene(embree_->device);
  // Not RTC_SCENE_FLAG_COMPACT: its leaves (indices into the vertex buffer) would save about 28
  // bytes a triangle, but it changed block-on-floor's golden render and the farm's bytes, and
  // the vertex buffer could not be released.
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);

  // Each geometry's buffers, shared with Embree: ours to release once the BVH is built.
  GeometryBuffers buffers[2];
  RTCGeometry geometry[2] = {nullptr, nullptr};
  for (int side = 0; side < 2; ++side) {
    if (triangle_count[side] == 0) continue;
    geometry[side] = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    buffers[side].Allocate(triangle_count[side], vertex_count[side]);
    rtcSetSharedGeometryBuffer(geometry[side], RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               buffers[side].vertices, 0, 3 * sizeof(float), vertex_count[side]);
    rtcSetSharedGeometryBuffer(geometry[side], RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               buffers[side].indices, 0, 3 * sizeof(unsigned),
                               triangle_count[side]);
    ThrowOnEmbreeError(embree_->device, "buffer allocation");
  }

  // Second pass: each patch gets its own corners as vertices, which a quad's two triangles share;
  // identical input coordinates map to identical floats, which is all watertightness needs. The
  // one-sided geometry's records come first in triangles_, then the two-sided's.
  two_sided_first_ = triangle_count[0];
  triangles_.resize(triangle_count[0] + triangle_count[1]);
  size_t v[2] = {0, 0}, t[2] = {0, 0};
  uint32_t patch = 0;
  patches([&](const PatchShape& p, bool two_sided) {
    float* vertices = buffers[two_sided].vertices;
    unsigned* indices = buffers[two_sided].indices;
    const size_t first = v[two_sided];
    for (int k = 0; k < p.corner_count; ++k) {
      const Vec3 corner = p.corners[k] - centre_;
      vertices[3 * (first + k) + 0] = static_cast<float>(corner.x);
      vertices[3 * (first + k) + 1] = static_cast<float>(corner.y);
      vertices[3 * (first + k) + 2] = static_cast<float>(corner.z);
    }
    auto emit = [&](size_t a, size_t b, size_t c) {
      const size_t corner[3] = {a, b, c};
      Vec3 as_float[3];  // the corners as Embree sees them
      for (int k = 0; k < 3; ++k) {
        indices[3 * t[two_sided] + k] = static_cast<unsigned>(corner[k]);
        const float* xyz = vertices + 3 * corner[k];
        as_float[k] = {xyz[0], xyz[1], xyz[2]};
      }
      triangles_[(two_sided ? two_sided_first_ : 0) + t[two_sided]] = {
          patch, NgMargin(as_float[0], as_float[1], as_float[2], p.normal, diagonal)};
      ++t[two_sided];
    };
    emit(first, first + 1, first + 2);
    if (p.corner_count == 4) emit(first, first + 2, first + 3);
    v[two_sided] += p.corner_count;
    ++patch;
  });
  if (patch != count || t[0] != triangle_count[0] || t[1] != triangle_count[1]) {
    throw std::invalid_argument("RayCaster: the stream changed between its passes");
  }

  for (unsigned side = 0; side < 2; ++side) {
    if (!geometry[side]) continue;
    if (side == 1) {
      rtcSetGeometryUserData(geometry[side], this);
      rtcSetGeometryIntersectFilterFunction(geometry[side], &RayCaster::FrontOnlyFilter);
    }
    rtcCommitGeometry(geometry[side]);
    rtcAttachGeometryByID(embree_->scene, geometry[side],
                          side == 1 ? kTwoSidedGeometry : kOneSidedGeometry);
    rtcReleaseGeometry(geometry[side]);
    ThrowOnEmbreeError(embree_->device, "geometry");
  }
  rtcCommitScene(embree_->scene);
  ThrowOnEmbreeError(embree_->device, "scene build");
  // The robust BVH's leaves hold copies of the triangles' corners (Embree 3's Triangle4v; only
  // RTC_SCENE_FLAG_COMPACT's leaves index the buffers): the buffers are no longer read.
  for (GeometryBuffers& b : buffers) b.Release();
  malloc_trim(0);  // the free pages in the middle of the heap too
}

bool RayCaster::MeetsFront(const Triangle& triangle, const Vec3& d, const Vec3& ng) const {
  const double cosine = Dot(d, ng);
  if (std::abs(cosine) > triangle.ng_margin * Length(ng)) return cosine < 0;
  return Dot(d, NormalOf(triangle.patch)) < 0;
}

void RayCaster::FrontOnlyFilter(const RTCFilterFunctionNArguments* args) {
  const auto* caster = static_cast<const RayCaster*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const Vec3 d{RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                 RTCRayN_dir_z(args->ray, args->N, i)};
    const Vec3 ng{RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
                  RTCHitN_Ng_z(args->hit, args->N, i)};
    const Triangle& triangle =
        caster->TriangleOf(kTwoSidedGeometry, RTCHitN_primID(args->hit, args->N, i));
    if (!caster->MeetsFront(triangle, d, ng)) args->valid[i] = 0;
  }
}

RayCaster::~RayCaster() = default;

float RayCaster::NgMargin(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& patch_normal,
                          double scene_diagonal) {
  // Embree's robust intersector takes Ng as a cross product of edges of the float triangle moved
  // to the ray's origin, in float: each edge is off by about 2^-23 (scene size), the product by a
  // few float ulps of |e1| |e2| more, so Ng's direction is within about 2^-21 (diagonal +
  // perimeter) perimeter / |cross| of the exact cross product of the float corners, which is
  // `off_plane` from the patch's normal. A ray d (|d| within 1e-6 of 1) then has Dot(d, patch
  // normal) of the sign of Dot(d, Ng / |Ng|) whenever the latter is further from 0 than their sum;
  // 2^-16 instead of 2^-21 and the factor 2 leave ample room.
  const Vec3 cross = Cross(b - a, c - a);
  const double area2 = Length(cross);
  const double perimeter = Length(b - a) + Length(c - b) + Length(a - c);
  if (!(area2 > 0) || !std::isfinite(area2)) return INFINITY;
  const double off_plane = Length(cross / area2 - patch_normal);
  const double rounding = 0x1.0p-16 * (scene_diagonal + perimeter) * perimeter / area2;
  const double margin = 2 * (off_plane + rounding);
  return margin < 0.5 ? static_cast<float>(margin) : INFINITY;
}

RTCSceneTy* RayCaster::embree_scene() const { return embree_->scene; }

void RayCaster::PrepareRay(const Vec3& origin, const Vec3& direction, const Vec3& surface_normal,
                           RTCRayHit* ray) const {
  const Vec3 o = origin - centre_ + surface_normal * origin_offset_;
  SetRay(static_cast<float>(o.x), static_cast<float>(o.y), static_cast<float>(o.z),
         static_cast<float>(direction.x), static_cast<float>(direction.y),
         static_cast<float>(direction.z), ray);
}

RayHit RayCaster::Trace(const Vec3& origin, const Vec3& direction,
                        const Vec3& surface_normal) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  PrepareRay(origin, direction, surface_normal, &rh);
  rtcIntersect1(embree_->scene, &context, &rh);
  RayHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.patch = TriangleOf(rh.hit.geomID, rh.hit.primID).patch;
  // The filter let only the front of a two-sided patch through.
  hit.front = rh.hit.geomID == kTwoSidedGeometry || Dot(direction, NormalOf(hit.patch)) < 0;
  return hit;
}

template <typename LiftOf>
void RayCaster::TraceLifted(const RayBlock& block, const LiftOf& lift_of, RayHit* hits) const {
  const int n = block.count;
  const int packed = n - n % kPacket;  // rays in whole packets; the rest are traced one by one
  const auto origin = [&](const double* coordinate, double centre, double lift_along, int i) {
    return static_cast<float>((coordinate[i] - centre) + lift_along);
  };
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int first = 0; first < packed; first += kPacket) {
    // Embree's records for 16 rays as structure of arrays, on the stack.
    alignas(64) RTCRayHit16 packet;
    alignas(64) int valid[kPacket];
    for (int l = 0; l < kPacket; ++l) {
      const int i = first + l;
      const Vec3 lift = lift_of(i);
      valid[l] = -1;
      packet.ray.org_x[l] = origin(block.origin_x, centre_.x, lift.x, i);
      packet.ray.org_y[l] = origin(block.origin_y, centre_.y, lift.y, i);
      packet.ray.org_z[l] = origin(block.origin_z, centre_.z, lift.z, i);
      packet.ray.dir_x[l] = static_cast<float>(block.direction_x[i]);
      packet.ray.dir_y[l] = static_cast<float>(block.direction_y[i]);
      packet.ray.dir_z[l] = static_cast<float>(block.direction_z[i]);
      packet.ray.tnear[l] = 0.0f;
      packet.ray.tfar[l] = INFINITY;
      packet.ray.time[l] = 0.0f;
      packet.ray.mask[l] = 0xffffffffu;
      packet.ray.id[l] = 0;
      packet.ray.flags[l] = 0;
      packet.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, embree_->scene, &context, &packet);
    for (int l = 0; l < kPacket; ++l) {
      if (packet.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID) {
        __builtin_prefetch(&TriangleOf(packet.hit.geomID[l], packet.hit.primID[l]));
      }
    }
    for (int l = 0; l < kPacket; ++l) {
      hits[first + l] = HitOf(block, first + l, packet.hit.geomID[l], packet.hit.primID[l],
                              {packet.hit.Ng_x[l], packet.hit.Ng_y[l], packet.hit.Ng_z[l]});
    }
  }
  // The last rays (fewer than a packet) one by one: a packet of a few rays costs about a full one.
  RTCRayHit rays[kPacket];
  for (int i = packed; i < n; ++i) {
    const Vec3 lift = lift_of(i);
    SetRay(origin(block.origin_x, centre_.x, lift.x, i),
           origin(block.origin_y, centre_.y, lift.y, i),
           origin(block.origin_z, centre_.z, lift.z, i), static_cast<float>(block.direction_x[i]),
           static_cast<float>(block.direction_y[i]), static_cast<float>(block.direction_z[i]),
           &rays[i - packed]);
  }
  for (int i = packed; i < n; ++i) {
    RTCRayHit& ray = rays[i - packed];
    rtcIntersect1(embree_->scene, &context, &ray);
    if (ray.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      __builtin_prefetch(&TriangleOf(ray.hit.geomID, ray.hit.primID));
    }
  }
  for (int i = packed; i < n; ++i) {
    const RTCHit& h = rays[i - packed].hit;
    hits[i] = HitOf(block, i, h.geomID, h.primID, {h.Ng_x, h.Ng_y, h.Ng_z});
  }
}

void RayCaster::TraceBlock(const RayBlock& block, const Vec3& surface_normal, RayHit* hits) const {
  const Vec3 lift = surface_normal * origin_offset_;  // as PrepareRay adds it
  TraceLifted(
      block, [&lift](int) { return lift; }, hits);
}

void RayCaster::TraceBlock(const RayBlock& block, const Vec3* surface_normals, RayHit* hits) const {
  TraceLifted(
      block, [&](int i) { return surface_normals[i] * origin_offset_; }, hits);
}

// The side comes from Embree's Ng unless the ray is too close to grazing for its sign to be
// certain (rarely: for a flat patch the margin is about 2^-15 scene size / patch size, a few
// thousandths of a cosine on the 50 mm Cornell box); then, as in Trace, from the patch normal.
RayHit RayCaster::HitOf(const RayBlock& block, int i, unsigned geometry, unsigned primitive,
                        const Vec3& ng) const {
  if (geometry == RTC_INVALID_GEOMETRY_ID) return RayHit{};
  const Triangle& triangle = TriangleOf(geometry, primitive);
  const Vec3 d{block.direction_x[i], block.direction_y[i], block.direction_z[i]};
  RayHit hit;
  hit.patch = triangle.patch;
  // The filter let only the front of a two-sided patch through.
  hit.front = geometry == kTwoSidedGeometry || MeetsFront(triangle, d, ng);
  return hit;
}

bool RayCaster::Unoccluded(const Vec3& origin, const Vec3& target,
                           const Vec3& surface_normal) const {
  const Vec3 lifted = origin + surface_normal * origin_offset_;
  const double distance = Length(target - lifted);
  if (!(distance > 0)) return true;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  PrepareRay(origin, (target - lifted) / distance, surface_normal, &rh);
  RTCRay& ray = rh.ray;
  ray.tfar = static_cast<float>(distance * (1 - kShadowRayMargin));
  rtcOccluded1(embree_->scene, &context, &ray);
  // Embree sets tfar to -inf when something is in the way.
  return ray.tfar >= 0;
}

void RayCaster::UnoccludedBlock(const Vec3& origin, const Vec3& surface_normal, const Vec3* targets,
                                int count, bool* unoccluded) const {
  const int packed = count - count % kPacket;
  // As Unoccluded and PrepareRay compute them.
  const Vec3 lifted = origin + surface_normal * origin_offset_;
  const Vec3 o = origin - centre_ + surface_normal * origin_offset_;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int first = 0; first < packed; first += kPacket) {
    alignas(64) RTCRay16 packet;
    alignas(64) int valid[kPacket];
    bool any = false;
    for (int l = 0; l < kPacket; ++l) {
      const int i = first + l;
      const double distance = Length(targets[i] - lifted);
      valid[l] = 0;
      if (!(distance > 0)) {
        unoccluded[i] = true;
        continue;
      }
      const Vec3 d = (targets[i] - lifted) / distance;
      valid[l] = -1;
      any = true;
      packet.org_x[l] = static_cast<float>(o.x);
      packet.org_y[l] = static_cast<float>(o.y);
      packet.org_z[l] = static_cast<float>(o.z);
      packet.dir_x[l] = static_cast<float>(d.x);
      packet.dir_y[l] = static_cast<float>(d.y);
      packet.dir_z[l] = static_cast<float>(d.z);
      packet.tnear[l] = 0.0f;
      packet.tfar[l] = static_cast<float>(distance * (1 - kShadowRayMargin));
      packet.time[l] = 0.0f;
      packet.mask[l] = 0xffffffffu;
      packet.id[l] = 0;
      packet.flags[l] = 0;
    }
    if (!any) continue;
    rtcOccluded16(valid, embree_->scene, &context, &packet);
    for (int l = 0; l < kPacket; ++l) {
      if (valid[l] != 0) unoccluded[first + l] = packet.tfar[l] >= 0;
    }
  }
  for (int i = packed; i < count; ++i)
    unoccluded[i] = Unoccluded(origin, targets[i], surface_normal);
}

}  // namespace radfarm
