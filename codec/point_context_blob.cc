#include "codec/point_context_blob.h"

#include <flatbuffers/flatbuffers.h>

#include <cmath>
#include <string>

#include "codec/decode_checks.h"
#include "codec/patch_scene_codec.h"
#include "point_context_generated.h"

namespace radfarm::codec {
namespace {

constexpr std::string_view kKind = "point context";
// Far above what the display fits (kPointShadowRays per point, a light's rays no more): a bound
// that keeps a damaged blob from asking for billions of shadow rays a point.
constexpr uint32_t kMaxRaysPerPoint = 1u << 16;

flatbuffers::Offset<flatbuffers::Vector<const wire::PointColour*>> Colours(
    flatbuffers::FlatBufferBuilder& fbb, const std::vector<Rgb>& values) {
  std::vector<wire::PointColour> out;
  out.reserve(values.size());
  for (const Rgb& c : values) out.emplace_back(c.r, c.g, c.b);
  return fbb.CreateVectorOfStructs(out);
}

Result<std::vector<Rgb>> ReadColours(const flatbuffers::Vector<const wire::PointColour*>& in,
                                     size_t expected, const char* field) {
  if (in.size() != expected) {
    return FieldError(kKind, field,
                      "holds " + std::to_string(in.size()) + " values where " +
                          std::to_string(expected) + " are due");
  }
  std::vector<Rgb> out;
  out.reserve(in.size());
  for (flatbuffers::uoffset_t i = 0; i < in.size(); ++i) {
    const wire::PointColour c = StructAt(in, i);
    out.push_back({c.r(), c.g(), c.b()});
    if (!IsFinite(out.back())) {
      return FieldError(kKind, std::string(field) + " " + std::to_string(i), "is not finite");
    }
  }
  return out;
}

Status ReadGathering(const wire::PointContextBlob& root, size_t patches, PointContext* context) {
  const bool any = root.outgoing() || root.corner_offsets() || root.bounced();
  if (!any) return Ok{};
  if (!root.outgoing() || !root.corner_offsets() || !root.bounced()) {
    return FieldError(kKind, "outgoing, corner_offsets and bounced", "are not all present");
  }
  if (patches == 0) return FieldError(kKind, "outgoing", "is present for a scene of no patches");
  Result<std::vector<Rgb>> outgoing = ReadColours(*root.outgoing(), patches, "outgoing");
  RADFARM_RETURN_IF_ERROR(outgoing);
  Result<std::vector<Rgb>> corners =
      ReadColours(*root.corner_offsets(), 4 * patches, "corner_offsets");
  RADFARM_RETURN_IF_ERROR(corners);
  Result<std::vector<Rgb>> bounced = ReadColours(*root.bounced(), patches, "bounced");
  RADFARM_RETURN_IF_ERROR(bounced);
  context->outgoing = std::move(*outgoing);
  context->bounced = std::move(*bounced);
  context->corner_offsets.resize(patches);
  for (size_t p = 0; p < patches; ++p) {
    for (size_t k = 0; k < 4; ++k) context->corner_offsets[p][k] = (*corners)[4 * p + k];
  }
  return Ok{};
}

}  // namespace

std::vector<uint8_t> EncodePointContext(std::span<const uint8_t> scene,
                                        const PointContext& context) {
  flatbuffers::FlatBufferBuilder fbb(1024 + scene.size() + context.outgoing.size() * 144);
  const auto scene_offset = fbb.CreateVector(scene.data(), scene.size());
  flatbuffers::Offset<flatbuffers::Vector<const wire::PointColour*>> outgoing, corners, bounced;
  if (context.gathers()) {
    outgoing = Colours(fbb, context.outgoing);
    std::vector<Rgb> flat;
    flat.reserve(4 * context.corner_offsets.size());
    for (const auto& offsets : context.corner_offsets)
      flat.insert(flat.end(), offsets.begin(), offsets.end());
    corners = Colours(fbb, flat);
    bounced = Colours(fbb, context.bounced);
  }
  fbb.Finish(wire::CreatePointContextBlob(fbb, scene_offset, context.emitters,
                                          context.rays_per_point, context.rays_per_light, outgoing,
                                          corners, bounced, context.second_reach),
             "RDPC");
  return {fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()};
}

Result<DecodedPointContext> DecodePointContext(std::span<const uint8_t> blob) {
  std::vector<uint8_t> aligned;
  Result<const wire::PointContextBlob*> verified = VerifiedRoot<wire::PointContextBlob>(
      blob, kKind, "RDPC", &wire::VerifyPointContextBlobBuffer, &aligned);
  RADFARM_RETURN_IF_ERROR(verified);
  const wire::PointContextBlob* root = *verified;
  DecodedPointContext out;
  const auto& scene = *root->scene();
  Result<PatchScene> decoded = DecodePatchScene({scene.data(), scene.size()});
  if (!decoded) return Error{std::string(kKind) + ": scene: " + decoded.error()};
  out.scene = std::move(*decoded);
  PointContext& context = out.context;
  context.emitters = root->emitters();
  context.rays_per_point = root->rays_per_point();
  context.rays_per_light = root->rays_per_light();
  context.second_reach = root->second_reach();
  if (context.rays_per_point < 1 || context.rays_per_point > kMaxRaysPerPoint) {
    return FieldError(kKind, "rays_per_point", "is out of range");
  }
  if (context.rays_per_light > kMaxRaysPerPoint) {
    return FieldError(kKind, "rays_per_light", "is out of range");
  }
  if (!std::isfinite(context.second_reach) || context.second_reach <= 0) {
    return FieldError(kKind, "second_reach", "is not a finite positive length");
  }
  RADFARM_RETURN_IF_ERROR(ReadGathering(*root, out.scene.patches.size(), &context));
  return out;
}

}  // namespace radfarm::codec
