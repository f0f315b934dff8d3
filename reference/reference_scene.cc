#include "reference/reference_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/embree_handles.h"
#include "mesh/ear_clip.h"
#include "mesh/polygon.h"

namespace radfarm::reference {

struct ReferenceScene::Embree : EmbreeHandles {};

namespace {

// A polygon's triangles as corner indices into `corners`: a fan when convex, ear clipping else.
std::vector<std::array<uint32_t, 3>> SplitPolygon(const std::vector<Vec3>& corners) {
  const size_t n = corners.size();
  std::vector<std::array<uint32_t, 3>> out;
  if (n < 3) return out;
  const Vec3 area = VectorArea(corners);
  const double length = Length(area);
  if (n == 3 || length == 0 || IsStrictlyConvex(corners, area / length)) {
    for (uint32_t i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
    return out;
  }
  return EarClip(ProjectToPlane(corners, corners[0], area / length)).triangles;
}

Vec3 ToEmbree(const Vec3& p, const Vec3& centre) { return p - centre; }

}  // namespace

ReferenceScene::~ReferenceScene() = default;

Result<std::unique_ptr<ReferenceScene>> ReferenceScene::Build(const InputScene& input) {
  std::unique_ptr<ReferenceScene> scene(new ReferenceScene());
  scene->materials_ = input.materials;
  scene->lights_ = input.lights;
  scene->sky_ = input.sky;
  Bounds3 bounds;
  for (uint32_t f = 0; f < input.faces.size(); ++f) {
    const InputFace& face = input.faces[f];
    std::vector<Vec3> corners;
    for (uint32_t i : face.indices) corners.push_back(input.positions[i]);
    for (const auto& t : SplitPolygon(corners)) {
      Triangle tri;
      tri.a = corners[t[0]];
      tri.ab = corners[t[1]] - tri.a;
      tri.ac = corners[t[2]] - tri.a;
      const Vec3 cross = Cross(tri.ab, tri.ac);
      tri.area = 0.5 * Length(cross);
      if (!(tri.area > 0)) continue;
      tri.normal = cross / (2 * tri.area);
      tri.material = face.material;
      tri.face = f;
      for (int k = 0; k < 3; ++k) bounds.Extend(corners[t[k]]);
      scene->triangles_.push_back(tri);
    }
  }
  if (scene->triangles_.empty()) return Error{input.path + ": no triangle of positive area"};
  scene->centre_ = bounds.Centre();
  scene->diagonal_ = bounds.Diagonal();
  scene->offset_ = std::max(scene->diagonal_, 1e-30) * 1e-6;

  // Emitters by area times emitted radiance.
  double total = 0;
  scene->emitter_probability_.assign(scene->triangles_.size(), 0);
  for (uint32_t t = 0; t < scene->triangles_.size(); ++t) {
    const Triangle& tri = scene->triangles_[t];
    const double power = tri.area * scene->materials_[tri.material].emission.Sum();
    if (power > 0) {
      scene->emitters_.push_back({t, power});
      total += power;
    }
  }
  double running = 0;
  for (Emitter& e : scene->emitters_) {
    e.probability /= total;
    running += e.probability;
    scene->emitter_cdf_.push_back(running);
    scene->emitter_probability_[e.triangle] = e.probability;
  }
  if (!scene->emitter_cdf_.empty()) scene->emitter_cdf_.back() = 1;
  scene->BuildBvh();
  return scene;
}

void ReferenceScene::BuildBvh() {
  embree_ = std::make_unique<Embree>();
  embree_->device = rtcNewDevice(nullptr);
  if (embree_->device == nullptr) throw std::runtime_error("Embree: no device");
  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = triangles_.size();
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t t = 0; t < n; ++t) {
    const Triangle& tri = triangles_[t];
    const Vec3 corners[3] = {tri.a, tri.a + tri.ab, tri.a + tri.ac};
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = ToEmbree(corners[k], centre_);
      vertices[9 * t + 3 * k + 0] = static_cast<float>(p.x);
      vertices[9 * t + 3 * k + 1] = static_cast<float>(p.y);
      vertices[9 * t + 3 * k + 2] = static_cast<float>(p.z);
      indices[3 * t + k] = static_cast<unsigned>(3 * t + k);
    }
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(embree_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(embree_->scene);
  ThrowOnEmbreeError(embree_->device, "building the reference scene");
}

SurfaceHit ReferenceScene::Trace(const Vec3& origin, const Vec3& direction,
                                 const Vec3& normal) const {
  const Vec3 o = ToEmbree(origin, centre_) + normal * offset_;
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(direction.x);
  rh.ray.dir_y = static_cast<float>(direction.y);
  rh.ray.dir_z = static_cast<float>(direction.z);
  rh.ray.tnear = 0;
  rh.ray.tfar = INFINITY;
  rh.ray.time = 0;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(embree_->scene, &context, &rh);
  SurfaceHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.triangle = rh.hit.primID;
  const Triangle& tri = triangles_[hit.triangle];
  // The hit point from the barycentrics on the double-precision triangle, not from t: it lies on
  // the surface, whatever the ray's float rounding.
  hit.position = tri.a + tri.ab * double(rh.hit.u) + tri.ac * double(rh.hit.v);
  hit.front = Dot(direction, tri.normal) < 0;
  return hit;
}

bool ReferenceScene::Unoccluded(const Vec3& origin, const Vec3& target, const Vec3& normal) const {
  const Vec3 o = ToEmbree(origin, centre_) + normal * offset_;
  const Vec3 d = ToEmbree(target, centre_) - o;
  const double distance = Length(d);
  if (!(distance > 0)) return true;
  RTCRay ray;
  ray.org_x = static_cast<float>(o.x);
  ray.org_y = static_cast<float>(o.y);
  ray.org_z = static_cast<float>(o.z);
  ray.dir_x = static_cast<float>(d.x / distance);
  ray.dir_y = static_cast<float>(d.y / distance);
  ray.dir_z = static_cast<float>(d.z / distance);
  ray.tnear = 0;
  // Stops short of the target so that its own surface does not count.
  ray.tfar = static_cast<float>(std::max(0.0, distance * (1 - 1e-5) - offset_));
  ray.time = 0;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(embree_->scene, &context, &ray);
  return ray.tfar >= 0;  // Embree sets tfar to -inf when something is in the way
}

const ReferenceScene::Emitter& ReferenceScene::PickEmitter(double u) const {
  const auto it = std::upper_bound(emitter_cdf_.begin(), emitter_cdf_.end(), u);
  const size_t k = std::min<size_t>(it - emitter_cdf_.begin(), emitters_.size() - 1);
  return emitters_[k];
}

void ApplyJobTwoSided(bool all, const std::map<std::string, bool>& per_material,
                      InputScene* scene) {
  for (Material& m : scene->materials) {
    if (all) m.two_sided = true;
    const auto it = per_material.find(m.name);
    if (it != per_material.end()) m.two_sided = it->second;
  }
}

}  // namespace radfarm::reference
