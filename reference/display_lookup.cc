#include "reference/display_lookup.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <stdexcept>

#include "core/embree_handles.h"

namespace radfarm::reference {

struct DisplayLookup::Embree : EmbreeHandles {};

namespace {

// What the filter needs: the triangle normals and the side the query looks from.
struct FilterContext {
  RTCIntersectContext context;  // first, so Embree's pointer is this struct's
  const std::vector<Vec3>* normals = nullptr;
  Vec3 side;
};

// Drops hits on triangles that do not face the query's side.
void FacingFilter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const FilterContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    if (Dot((*ctx->normals)[prim], ctx->side) <= 0) args->valid[i] = 0;
  }
}

}  // namespace

DisplayLookup::DisplayLookup(DisplayPly display, double reach)
    : display_(std::move(display)), reach_(reach), embree_(std::make_unique<Embree>()) {
  Bounds3 bounds;
  for (const Vec3& p : display_.positions) bounds.Extend(p);
  centre_ = bounds.Empty() ? Vec3{} : bounds.Centre();
  embree_->device = rtcNewDevice(nullptr);
  if (embree_->device == nullptr) throw std::runtime_error("Embree: no device");
  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneFlags(embree_->scene,
                   RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t nv = display_.positions.size(), nt = display_.triangles.size();
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
  for (size_t v = 0; v < nv; ++v) {
    const Vec3 p = display_.positions[v] - centre_;
    vertices[3 * v] = float(p.x);
    vertices[3 * v + 1] = float(p.y);
    vertices[3 * v + 2] = float(p.z);
  }
  for (size_t t = 0; t < nt; ++t) {
    const auto& tri = display_.triangles[t];
    for (int k = 0; k < 3; ++k) indices[3 * t + k] = tri[k];
    const Vec3& a = display_.positions[tri[0]];
    const Vec3 c = Cross(display_.positions[tri[1]] - a, display_.positions[tri[2]] - a);
    const double length = Length(c);
    normals_.push_back(length > 0 ? c / length : Vec3{});
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(embree_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(embree_->scene);
  ThrowOnEmbreeError(embree_->device, "building the display BVH");
}

DisplayLookup::~DisplayLookup() = default;

std::optional<Rgb> DisplayLookup::RadianceAt(const Vec3& p, const Vec3& n) const {
  if (auto facing = Find(p, n, true)) return facing;
  return Find(p, n, false);
}

std::optional<Rgb> DisplayLookup::Find(const Vec3& p, const Vec3& n, bool facing_only) const {
  const Vec3 o = p - centre_ + n * reach_;
  RTCRayHit rh;
  rh.ray.org_x = float(o.x);
  rh.ray.org_y = float(o.y);
  rh.ray.org_z = float(o.z);
  rh.ray.dir_x = float(-n.x);
  rh.ray.dir_y = float(-n.y);
  rh.ray.dir_z = float(-n.z);
  rh.ray.tnear = 0;
  rh.ray.tfar = float(2 * reach_);
  rh.ray.time = 0;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  FilterContext ctx;
  rtcInitIntersectContext(&ctx.context);
  if (facing_only) ctx.context.filter = &FacingFilter;
  ctx.normals = &normals_;
  ctx.side = n;
  rtcIntersect1(embree_->scene, &ctx.context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  const auto& tri = display_.triangles[rh.hit.primID];
  const double u = rh.hit.u, v = rh.hit.v;
  return display_.radiance[tri[0]] * (1 - u - v) + display_.radiance[tri[1]] * u +
         display_.radiance[tri[2]] * v;
}

}  // namespace radfarm::reference
