#include "codec/job_bundle.h"

#include <flatbuffers/flatbuffers.h>

#include <algorithm>
#include <array>
#include <limits>
#include <string>

#include "base/result.h"
#include "codec/decode_checks.h"
#include "codec/punctual_light_codec.h"
#include "codec/sky_codec.h"
#include "job/output_budget.h"
#include "job_bundle_generated.h"
#include "output/illuminance_plane.h"

namespace radfarm::codec {
namespace {

constexpr std::string_view kKind = "job bundle";
constexpr uint32_t kMaxFaces = 1u << 26;
constexpr uint32_t kMaxFaceCorners = 1u << 16;

wire::BundlePoint ToWire(const Vec3& v) { return {v.x, v.y, v.z}; }
wire::BundleColour ToWire(const Rgb& c) { return {c.r, c.g, c.b}; }
Vec3 FromWire(const wire::BundlePoint* p) { return p ? Vec3{p->x(), p->y(), p->z()} : Vec3{}; }
Rgb FromWire(const wire::BundleColour* c) { return c ? Rgb{c->r(), c->g(), c->b()} : Rgb{}; }

Error Bad(const std::string& field, std::string_view what) {
  return FieldError(kKind, field, what);
}

Status DecodeSolver(const wire::BundleSolver& in, SolverSettings* out) {
  if (in.sampler() > static_cast<uint8_t>(SamplerKind::kSobol)) {
    return Bad("solver.sampler", "is not a known sampler");
  }
  out->sampler = static_cast<SamplerKind>(in.sampler());
  out->seed = in.seed();
  out->tolerance = in.tolerance();
  out->max_rays = in.max_rays();
  out->max_seconds = in.max_seconds();
  out->shot_rays = in.shot_rays();
  out->min_shooter_rays = in.min_shooter_rays();
  out->shooters_per_round = in.shooters_per_round();
  out->grid_step_degrees = in.grid_step_degrees();
  out->threads = in.threads();
  out->overrelaxation = in.overrelaxation();
  out->gather_rays = in.gather_rays();
  if (!(out->tolerance > 0 && out->tolerance < 1)) return Bad("solver.tolerance", "not in (0, 1)");
  if (!(out->max_seconds >= 0) || !std::isfinite(out->max_seconds)) {
    return Bad("solver.seconds", "is negative or not finite");
  }
  if (out->min_shooter_rays < 1) return Bad("solver.min_shooter_rays", "is below 1");
  if (!(out->grid_step_degrees > 0 && out->grid_step_degrees <= 90)) {
    return Bad("solver.grid_step_degrees", "not in (0, 90]");
  }
  if (!IsValidOverrelaxation(out->overrelaxation)) {
    return Bad("solver.overrelaxation", "not in [1, 2)");
  }
  if (out->gather_rays > kMaxGatherRays) return Bad("solver.gather_rays", "is above 2^20");
  if (out->threads > kMaxSolverThreads) return Bad("solver.threads", "is above 65536");
  return Ok{};
}

// The loader's ranges (job/job_file.cc); ResolveRefineSettings checks the rest against the
// mesh.
Status DecodeRefine(const wire::BundleRefine* in, RefineSettings* out) {
  if (in == nullptr) return Ok{};  // refinement off: the defaults
  out->enabled = in->enabled();
  out->tolerance = in->tolerance();
  out->min_element_size = in->min_element_size();
  out->max_elements = in->max_elements();
  if (!(out->tolerance > 0) || !std::isfinite(out->tolerance)) {
    return Bad("mesh.refine_tolerance", "is not a finite number above 0");
  }
  if (!(out->min_element_size >= 0) || !std::isfinite(out->min_element_size)) {
    return Bad("mesh.min_element_size", "is negative or not finite");
  }
  if (out->max_elements > uint64_t{std::numeric_limits<int64_t>::max()}) {
    return Bad("mesh.max_elements", "is above 2^63 - 1");
  }
  return Ok{};
}

// The loader's ranges (job/job_file.cc): a size or a texel, each 0 when unset.
Status DecodeLightmapSettings(const wire::JobBundleBlob& in, Job* out) {
  out->lightmap_size = in.lightmap_size();
  out->lightmap_texel = in.lightmap_texel();
  if (!IsValidLightmapSize(out->lightmap_size)) {
    return Bad("output.lightmap_size", "is not " + LightmapSizeRange());
  }
  if (!(out->lightmap_texel >= 0) || !std::isfinite(out->lightmap_texel)) {
    return Bad("output.lightmap_texel", "is negative or not finite");
  }
  if (out->lightmap_size > 0 && out->lightmap_texel > 0) {
    return Bad("output.lightmap_texel", "is set with output.lightmap_size");
  }
  return Ok{};
}

// The loader's rules (output/illuminance_plane.h), and unique names as in the job file.
Status DecodeIlluminance(const wire::JobBundleBlob& in, Job* out) {
  if (in.illuminance() == nullptr) return Ok{};
  for (flatbuffers::uoffset_t i = 0; i < in.illuminance()->size(); ++i) {
    const wire::BundleIlluminancePlane* p = in.illuminance()->Get(i);
    const std::string field = "illuminance[" + std::to_string(i) + "]";
    IlluminancePlane plane{p->name()->str(), p->height(), p->spacing(), {}};
    if (p->surfaces() != nullptr) {
      for (const flatbuffers::String* pattern : *p->surfaces()) {
        plane.surfaces.push_back(pattern->str());
      }
    }
    const std::string problem = IlluminancePlaneProblem(plane);
    if (!problem.empty()) return Bad(field, problem);
    for (const IlluminancePlane& other : out->illuminance) {
      if (other.name == plane.name) return Bad(field, "repeats an earlier plane's name");
    }
    out->illuminance.push_back(std::move(plane));
  }
  return Ok{};
}

Status DecodeCamera(const wire::BundleCamera& in, Camera* out) {
  out->automatic = in.automatic();
  out->eye = FromWire(in.eye());
  out->target = FromWire(in.target());
  out->up = FromWire(in.up());
  out->fov_degrees = in.fov_degrees();
  out->width = in.width();
  out->height = in.height();
  out->exposure = in.exposure();
  out->auto_exposure = in.auto_exposure();
  out->samples_per_pixel = in.samples_per_pixel();
  if (!IsFinite(out->eye) || !IsFinite(out->target) || !IsFinite(out->up)) {
    return Bad("camera", "has a non-finite eye, target or up");
  }
  if (!(out->fov_degrees > 0 && out->fov_degrees < 180))
    return Bad("camera.fov", "not in (0, 180)");
  if (out->width < 1 || out->width > 16384 || out->height < 1 || out->height > 16384) {
    return Bad("camera.width/height", "not in [1, 16384]");
  }
  if (!std::isfinite(out->exposure)) return Bad("camera.exposure", "is not finite");
  if (out->samples_per_pixel < 1 || out->samples_per_pixel > 1024) {
    return Bad("camera.samples_per_pixel", "not in [1, 1024]");
  }
  if (Status budget = CheckPixelSamples(*out); !budget) {
    return Error{std::string(kKind) + ": " + budget.error()};
  }
  return Ok{};
}

Status DecodeScene(const wire::JobBundleBlob& in, InputScene* scene) {
  const auto& positions = *in.positions();
  for (flatbuffers::uoffset_t i = 0; i < positions.size(); ++i) {
    const wire::BundlePoint p = StructAt(positions, i);
    const Vec3 v{p.x(), p.y(), p.z()};
    if (!IsFinite(v)) {
      return Bad("positions[" + std::to_string(scene->positions.size()) + "]", "is not finite");
    }
    scene->positions.push_back(v);
  }
  for (const auto* m : *in.materials()) {
    Material material{m->name()->str(), FromWire(m->diffuse()), FromWire(m->emission()),
                      m->two_sided()};
    const std::string field = "material '" + material.name + "'";
    if (!IsReflectance(material.diffuse)) return Bad(field, "reflectance Kd outside [0, 1)");
    if (!IsNonNegative(material.emission)) return Bad(field, "emission Ke negative or not finite");
    scene->materials.push_back(std::move(material));
  }
  if (in.faces()->size() > kMaxFaces) return Bad("faces", "too many");
  for (const auto* f : *in.faces()) {
    const std::string field = "face " + std::to_string(scene->faces.size());
    InputFace face;
    if (f->indices()->size() < 3 || f->indices()->size() > kMaxFaceCorners) {
      return Bad(field, "has fewer than 3 or too many corners");
    }
    for (uint32_t index : *f->indices()) {
      if (index >= scene->positions.size()) return Bad(field, "index out of range");
      face.indices.push_back(index);
    }
    if (f->material() >= scene->materials.size()) return Bad(field, "material out of range");
    face.material = f->material();
    face.line = f->line();
    face.object = f->object();
    if (face.object >= std::max<size_t>(scene->objects.size(), 1)) {
      return Bad(field, "object out of range");
    }
    if (const auto* uv = f->lightmap_uv(); uv != nullptr) {
      if (uv->size() != 2 * face.indices.size()) return Bad(field, "lightmap UVs not 2 per corner");
      for (uint32_t k = 0; k < uv->size(); k += 2) {
        const float u = ScalarAt(*uv, k), v = ScalarAt(*uv, k + 1);
        if (!std::isfinite(u) || !std::isfinite(v)) return Bad(field, "lightmap UV not finite");
        face.lightmap_uv.push_back({u, v});
      }
    }
    scene->faces.push_back(std::move(face));
  }
  return Ok{};
}

// A matrix is 16 finite values or absent (identity).
Status DecodeMatrix(const flatbuffers::Vector<double>* in, const std::string& field,
                    std::array<double, 16>* out) {
  if (in == nullptr) return Ok{};
  if (in->size() != 16) return Bad(field, "is not 16 values");
  for (uint32_t i = 0; i < 16; ++i) {
    const double value = ScalarAt(*in, i);
    if (!std::isfinite(value)) return Bad(field, "is not finite");
    (*out)[i] = value;
  }
  return Ok{};
}

Status DecodeObjects(const wire::JobBundleBlob& in, InputScene* scene) {
  if (in.objects() == nullptr) return Ok{};
  if (in.objects()->size() > kMaxFaces) return Bad("objects", "too many");
  for (const auto* o : *in.objects()) {
    const std::string field = "object " + std::to_string(scene->objects.size());
    InputObject object;
    if (o->name() != nullptr) object.name = o->name()->str();
    object.parent = o->parent();
    if (object.parent < -1 || object.parent >= static_cast<int64_t>(scene->objects.size())) {
      return Bad(field, "parent is not an earlier object");
    }
    RADFARM_RETURN_IF_ERROR(DecodeMatrix(o->local(), field + " local", &object.local));
    RADFARM_RETURN_IF_ERROR(DecodeMatrix(o->world(), field + " world", &object.world));
    object.has_faces = o->has_faces();
    scene->objects.push_back(std::move(object));
  }
  return Ok{};
}

}  // namespace

std::vector<uint8_t> EncodeJobBundle(const JobBundle& bundle) {
  const Job& job = bundle.job;
  const InputScene& scene = bundle.scene;
  flatbuffers::FlatBufferBuilder fbb(4096 + scene.positions.size() * 24 + scene.faces.size() * 40);
  const auto path = fbb.CreateString(job.scene_path);
  const SolverSettings& s = job.solver;
  const auto solver = wire::CreateBundleSolver(
      fbb, static_cast<uint8_t>(s.sampler), s.seed, s.tolerance, s.max_rays, s.max_seconds,
      s.shot_rays, s.min_shooter_rays, s.shooters_per_round, s.grid_step_degrees, s.threads,
      s.overrelaxation, s.gather_rays);
  const Camera& c = job.camera;
  const wire::BundlePoint eye = ToWire(c.eye), target = ToWire(c.target), up = ToWire(c.up);
  const auto camera =
      wire::CreateBundleCamera(fbb, c.automatic, &eye, &target, &up, c.fov_degrees, c.width,
                               c.height, c.exposure, c.auto_exposure, c.samples_per_pixel);
  std::vector<wire::BundlePoint> points;
  points.reserve(scene.positions.size());
  for (const Vec3& v : scene.positions) points.push_back(ToWire(v));
  const auto positions = fbb.CreateVectorOfStructs(points);
  std::vector<flatbuffers::Offset<wire::BundleMaterial>> materials;
  for (const Material& m : scene.materials) {
    const auto name = fbb.CreateString(m.name);
    const wire::BundleColour kd = ToWire(m.diffuse), ke = ToWire(m.emission);
    materials.push_back(wire::CreateBundleMaterial(fbb, name, &kd, &ke, m.two_sided));
  }
  const auto material_vec = fbb.CreateVector(materials);
  std::vector<flatbuffers::Offset<wire::BundleFace>> faces;
  faces.reserve(scene.faces.size());
  for (const InputFace& f : scene.faces) {
    flatbuffers::Offset<flatbuffers::Vector<float>> lightmap_uv = 0;
    if (!f.lightmap_uv.empty()) {
      std::vector<float> flat;
      for (const auto& uv : f.lightmap_uv) flat.insert(flat.end(), uv.begin(), uv.end());
      lightmap_uv = fbb.CreateVector(flat);
    }
    const auto indices = fbb.CreateVector(f.indices);
    faces.push_back(
        wire::CreateBundleFace(fbb, indices, f.material, f.line, f.object, lightmap_uv));
  }
  const auto face_vec = fbb.CreateVector(faces);
  flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<wire::BundleObject>>> object_vec = 0;
  if (!scene.objects.empty()) {
    std::vector<flatbuffers::Offset<wire::BundleObject>> objects;
    for (const InputObject& o : scene.objects) {
      const auto matrix = [&fbb](const std::array<double, 16>& m) {
        if (m == InputObject::kIdentityMatrix)
          return flatbuffers::Offset<flatbuffers::Vector<double>>();
        return fbb.CreateVector(m.data(), m.size());
      };
      const auto name = fbb.CreateString(o.name);
      const auto local = matrix(o.local), world = matrix(o.world);
      objects.push_back(wire::CreateBundleObject(fbb, name, o.parent, local, world, o.has_faces));
    }
    object_vec = fbb.CreateVector(objects);
  }
  flatbuffers::Offset<wire::BundleRefine> refine = 0;
  if (job.refine.enabled) {
    refine = wire::CreateBundleRefine(fbb, true, job.refine.tolerance, job.refine.min_element_size,
                                      job.refine.max_elements);
  }
  const auto lights = EncodeLights(fbb, scene.lights);
  flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<wire::BundleIlluminancePlane>>>
      illuminance = 0;
  if (!job.illuminance.empty()) {
    std::vector<flatbuffers::Offset<wire::BundleIlluminancePlane>> planes;
    for (const IlluminancePlane& p : job.illuminance) {
      const auto name = fbb.CreateString(p.name);
      const auto surfaces = p.surfaces.empty() ? 0 : fbb.CreateVectorOfStrings(p.surfaces);
      planes.push_back(
          wire::CreateBundleIlluminancePlane(fbb, name, p.height, p.spacing, surfaces));
    }
    illuminance = fbb.CreateVector(planes);
  }
  fbb.Finish(wire::CreateJobBundleBlob(fbb, path, job.mesh.patch_size, solver, camera, positions,
                                       material_vec, face_vec, refine, lights, object_vec,
                                       job.lightmap_size, job.lightmap_texel, illuminance,
                                       EncodeSky(fbb, scene.sky)),
             "RDJB");
  return {fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()};
}

Result<JobBundle> DecodeJobBundle(std::span<const uint8_t> blob) {
  std::vector<uint8_t> aligned;
  flatbuffers::Verifier::Options options;
  options.max_tables = 2 * kMaxFaces;
  Result<const wire::JobBundleBlob*> verified = VerifiedRoot<wire::JobBundleBlob>(
      blob, kKind, "RDJB", &wire::VerifyJobBundleBlobBuffer, &aligned, options);
  RADFARM_RETURN_IF_ERROR(verified);
  const wire::JobBundleBlob* root = *verified;
  JobBundle bundle;
  bundle.job.scene_path = root->scene_path()->str();
  bundle.scene.path = bundle.job.scene_path;
  bundle.job.mesh.patch_size = root->patch_size();
  if (!(bundle.job.mesh.patch_size >= 0) || !std::isfinite(bundle.job.mesh.patch_size)) {
    return Bad("mesh.patch_size", "is negative or not finite");
  }
  RADFARM_RETURN_IF_ERROR(DecodeSolver(*root->solver(), &bundle.job.solver));
  RADFARM_RETURN_IF_ERROR(DecodeCamera(*root->camera(), &bundle.job.camera));
  RADFARM_RETURN_IF_ERROR(DecodeRefine(root->refine(), &bundle.job.refine));
  RADFARM_RETURN_IF_ERROR(DecodeLightmapSettings(*root, &bundle.job));
  RADFARM_RETURN_IF_ERROR(DecodeIlluminance(*root, &bundle.job));
  RADFARM_RETURN_IF_ERROR(DecodeObjects(*root, &bundle.scene));
  RADFARM_RETURN_IF_ERROR(DecodeScene(*root, &bundle.scene));
  Result<std::vector<PunctualLight>> lights = DecodeLights(root->lights(), kKind);
  RADFARM_RETURN_IF_ERROR(lights);
  bundle.scene.lights = std::move(*lights);
  Result<Sky> sky = DecodeSky(root->sky(), kKind);
  RADFARM_RETURN_IF_ERROR(sky);
  bundle.scene.sky = *sky;
  return bundle;
}

}  // namespace radfarm::codec
