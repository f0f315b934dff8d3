#include "codec/patch_scene_codec.h"

#include <flatbuffers/flatbuffers.h>

#include <string>
#include <utility>

#include "base/result.h"
#include "codec/decode_checks.h"
#include "codec/punctual_light_codec.h"
#include "codec/sky_codec.h"
#include "patch_scene_generated.h"

namespace radfarm::codec {
namespace {

constexpr std::string_view kKind = "scene blob";
constexpr uint32_t kMaxPatches = 1u << 26;

wire::Point ToWire(const Vec3& v) { return {v.x, v.y, v.z}; }
wire::Colour ToWire(const Rgb& c) { return {c.r, c.g, c.b}; }
Vec3 FromWire(const wire::Point* p) { return p ? Vec3{p->x(), p->y(), p->z()} : Vec3{}; }
Rgb FromWire(const wire::Colour* c) { return c ? Rgb{c->r(), c->g(), c->b()} : Rgb{}; }

Result<Patch> DecodePatch(const wire::ScenePatch& in, uint32_t index, size_t material_count) {
  const std::string field = "patch " + std::to_string(index);
  Patch p;
  const auto* corners = in.corners();
  if (corners->size() < 3 || corners->size() > 4) {
    return FieldError(kKind, field,
                      "has " + std::to_string(corners->size()) + " corners (expected 3 or 4)");
  }
  p.corner_count = static_cast<uint8_t>(corners->size());
  for (uint32_t k = 0; k < corners->size(); ++k) {
    const wire::Point corner = StructAt(*corners, k);
    p.corners[k] = FromWire(&corner);
  }
  p.normal = FromWire(in.normal());
  p.centre = FromWire(in.centre());
  p.area = in.area();
  p.reflectance = FromWire(in.reflectance());
  p.emission = FromWire(in.emission());
  p.surface = in.surface();
  p.material = in.material();
  p.two_sided = in.two_sided();
  for (uint32_t k = 0; k < p.corner_count; ++k) {
    if (!IsFinite(p.corners[k])) return FieldError(kKind, field, "has a non-finite corner");
  }
  if (!IsFinite(p.normal) || !IsFinite(p.centre)) {
    return FieldError(kKind, field, "has a non-finite normal or centre");
  }
  const double n = Length(p.normal);
  if (!(n > 0.999 && n < 1.001)) return FieldError(kKind, field, "normal is not a unit vector");
  if (!(p.area > 0) || !std::isfinite(p.area)) {
    return FieldError(kKind, field, "area is not a positive finite number");
  }
  if (!IsReflectance(p.reflectance)) {
    return FieldError(kKind, field, "reflectance is outside [0, 1)");
  }
  if (!IsNonNegative(p.emission)) {
    return FieldError(kKind, field, "emission is negative or not finite");
  }
  if (p.material >= material_count) {
    return FieldError(kKind, field,
                      "material " + std::to_string(p.material) + " is out of range (" +
                          std::to_string(material_count) + " materials)");
  }
  return p;
}

}  // namespace

std::vector<uint8_t> EncodePatchScene(const PatchScene& scene) {
  std::vector<uint8_t> blob;
  EncodePatchScene(
      scene, [&](std::span<const uint8_t> bytes) { blob.assign(bytes.begin(), bytes.end()); });
  return blob;
}

void EncodePatchScene(const PatchScene& scene,
                      const std::function<void(std::span<const uint8_t> blob)>& use) {
  flatbuffers::FlatBufferBuilder fbb(1024 + scene.patches.size() * 256);
  std::vector<flatbuffers::Offset<wire::ScenePatch>> patches;
  patches.reserve(scene.patches.size());
  for (const Patch& p : scene.patches) {
    std::vector<wire::Point> corners;
    for (uint32_t k = 0; k < p.corner_count; ++k) corners.push_back(ToWire(p.corners[k]));
    const auto corner_vec = fbb.CreateVectorOfStructs(corners);
    const wire::Point normal = ToWire(p.normal), centre = ToWire(p.centre);
    const wire::Colour reflectance = ToWire(p.reflectance), emission = ToWire(p.emission);
    patches.push_back(wire::CreateScenePatch(fbb, corner_vec, &normal, &centre, p.area,
                                             &reflectance, &emission, p.surface, p.material,
                                             p.two_sided));
  }
  const auto patch_vec = fbb.CreateVector(patches);
  const auto names = fbb.CreateVectorOfStrings(scene.material_names);
  const auto lights = EncodeLights(fbb, scene.lights);
  const auto sky = EncodeSky(fbb, scene.sky);
  fbb.Finish(wire::CreatePatchSceneBlob(fbb, patch_vec, names, lights, sky), "RDPS");
  use(std::span<const uint8_t>(fbb.GetBufferPointer(), fbb.GetSize()));
}

namespace {

// DecodePatches, with FlatBuffers' verification of the whole buffer or without.
Result<uint32_t> Decode(
    std::span<const uint8_t> blob, bool verify,
    const std::function<void(const Patch& patch, uint32_t index, uint32_t count)>& each,
    PatchScene* rest) {
  RADFARM_RETURN_IF_ERROR(CheckBlobHeader(blob, kKind, "RDPS"));
  std::vector<uint8_t> aligned;
  blob = Aligned(blob, &aligned);
  if (verify) {
    flatbuffers::Verifier::Options options;
    options.max_tables = 2 * kMaxPatches;
    flatbuffers::Verifier verifier(blob.data(), blob.size(), options);
    if (!wire::VerifyPatchSceneBlobBuffer(verifier)) {
      return Error{std::string(kKind) + ": not a valid FlatBuffer (verification failed)"};
    }
  }
  const wire::PatchSceneBlob* root = wire::GetPatchSceneBlob(blob.data());
  std::vector<std::string> material_names;
  for (const auto* name : *root->material_names()) material_names.push_back(name->str());
  const auto* patches = root->patches();
  if (patches->size() == 0) return Error{std::string(kKind) + ": has no patches"};
  if (patches->size() > kMaxPatches) return Error{std::string(kKind) + ": too many patches"};
  for (uint32_t i = 0; i < patches->size(); ++i) {
    Result<Patch> p = DecodePatch(*patches->Get(i), i, material_names.size());
    RADFARM_RETURN_IF_ERROR(p);
    each(*p, i, patches->size());
  }
  Result<std::vector<PunctualLight>> lights = DecodeLights(root->lights(), kKind);
  RADFARM_RETURN_IF_ERROR(lights);
  Result<Sky> sky = DecodeSky(root->sky(), kKind);
  RADFARM_RETURN_IF_ERROR(sky);
  if (rest) {
    rest->material_names = std::move(material_names);
    rest->lights = std::move(*lights);
    rest->sky = *sky;
  }
  return patches->size();
}

}  // namespace

Result<uint32_t> DecodePatches(
    std::span<const uint8_t> blob,
    const std::function<void(const Patch& patch, uint32_t index, uint32_t count)>& each,
    PatchScene* rest) {
  return Decode(blob, true, each, rest);
}

Result<uint32_t> DecodeAcceptedPatches(
    std::span<const uint8_t> blob,
    const std::function<void(const Patch& patch, uint32_t index, uint32_t count)>& each) {
  return Decode(blob, false, each, nullptr);
}

Result<PatchScene> DecodePatchScene(std::span<const uint8_t> blob) {
  PatchScene scene;
  std::vector<Patch>& patches = scene.patches;
  Result<uint32_t> count = DecodePatches(
      blob,
      [&patches](const Patch& p, uint32_t index, uint32_t count) {
        if (index == 0) patches.reserve(count);
        patches.push_back(p);
      },
      &scene);
  RADFARM_RETURN_IF_ERROR(count);
  return scene;
}

}  // namespace radfarm::codec
