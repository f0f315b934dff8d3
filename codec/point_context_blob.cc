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

wire::ScoreVec Wire(const Vec3& v) { return {v.x, v.y, v.z}; }
wire::PointColour Wire(const Rgb& c) { return {c.r, c.g, c.b}; }
Vec3 Read(const wire::ScoreVec& v) { return {v.x(), v.y(), v.z()}; }
Rgb Read(const wire::PointColour& c) { return {c.r(), c.g(), c.b()}; }

void WriteScoring(flatbuffers::FlatBufferBuilder& fbb, const LightScoreWork& work,
                  flatbuffers::Offset<flatbuffers::Vector<const wire::ScoreSource*>>* sources,
                  flatbuffers::Offset<flatbuffers::Vector<const wire::ScoreElement*>>* elements) {
  std::vector<wire::ScoreSource> s;
  s.reserve(work.sources.size());
  for (const LightSource& l : work.sources) {
    s.emplace_back(Wire(l.samples[0]), Wire(l.samples[1]), Wire(l.samples[2]), Wire(l.samples[3]),
                   Wire(l.normal), l.sample_area, Wire(l.unshot), l.surface);
  }
  *sources = fbb.CreateVectorOfStructs(s);
  std::vector<wire::ScoreElement> e;
  e.reserve(work.elements.size());
  for (const ScoredElement& x : work.elements) {
    const auto& c = x.shape.corners;
    e.emplace_back(Wire(c[0]), Wire(c[1]), Wire(c[2]), Wire(c[3]), x.shape.corner_count,
                   Wire(x.shape.normal), Wire(x.shape.centre), Wire(x.reflectance), x.surface,
                   Wire(x.radiosity));
  }
  *elements = fbb.CreateVectorOfStructs(e);
}

Status ReadScoring(const wire::PointContextBlob& root, LightScoreWork* work) {
  if (!root.score_sources() && !root.score_elements()) return Ok{};
  if (!root.score_sources() || !root.score_elements()) {
    return FieldError(kKind, "score_sources and score_elements", "are not both present");
  }
  const auto& sources = *root.score_sources();
  const auto& elements = *root.score_elements();
  if (sources.size() < 1 || sources.size() > kLightSources) {
    return FieldError(kKind, "score_sources",
                      "holds " + std::to_string(sources.size()) + " sources, not 1.." +
                          std::to_string(kLightSources));
  }
  if (elements.size() < 1 || elements.size() > kMaxScoreElements) {
    return FieldError(kKind, "score_elements",
                      "holds " + std::to_string(elements.size()) + " elements, not 1.." +
                          std::to_string(kMaxScoreElements));
  }
  work->tolerance = root.score_tolerance();
  if (!std::isfinite(work->tolerance) || work->tolerance <= 0) {
    return FieldError(kKind, "score_tolerance", "is not a finite number > 0");
  }
  for (flatbuffers::uoffset_t i = 0; i < sources.size(); ++i) {
    const wire::ScoreSource s = StructAt(sources, i);
    LightSource l;
    l.samples = {Read(s.sample0()), Read(s.sample1()), Read(s.sample2()), Read(s.sample3())};
    l.normal = Read(s.normal());
    l.sample_area = s.sample_area();
    l.unshot = Read(s.unshot());
    l.surface = s.surface();
    bool finite = IsFinite(l.normal) && IsFinite(l.unshot) && std::isfinite(l.sample_area) &&
                  l.sample_area >= 0;
    for (const Vec3& v : l.samples) finite = finite && IsFinite(v);
    if (!finite) {
      return FieldError(kKind, "score_sources " + std::to_string(i),
                        "holds a value not finite (or a negative area)");
    }
    work->sources.push_back(l);
  }
  work->elements.reserve(elements.size());
  for (flatbuffers::uoffset_t i = 0; i < elements.size(); ++i) {
    const wire::ScoreElement w = StructAt(elements, i);
    ScoredElement e;
    e.shape.corners = {Read(w.corner0()), Read(w.corner1()), Read(w.corner2()), Read(w.corner3())};
    e.shape.corner_count = w.corner_count();
    e.shape.normal = Read(w.normal());
    e.shape.centre = Read(w.centre());
    e.reflectance = Read(w.reflectance());
    e.surface = w.surface();
    e.radiosity = Read(w.radiosity());
    bool finite = IsFinite(e.shape.normal) && IsFinite(e.shape.centre) && IsFinite(e.reflectance) &&
                  IsFinite(e.radiosity);
    for (const Vec3& v : e.shape.corners) finite = finite && IsFinite(v);
    if (!finite) {
      return FieldError(kKind, "score_elements " + std::to_string(i), "holds a value not finite");
    }
    if (e.shape.corner_count != 3 && e.shape.corner_count != 4) {
      return FieldError(kKind, "score_elements " + std::to_string(i),
                        "has " + std::to_string(e.shape.corner_count) + " corners, not 3 or 4");
    }
    work->elements.push_back(e);
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
  flatbuffers::Offset<flatbuffers::Vector<const wire::ScoreSource*>> score_sources;
  flatbuffers::Offset<flatbuffers::Vector<const wire::ScoreElement*>> score_elements;
  if (!context.scoring.elements.empty()) {
    WriteScoring(fbb, context.scoring, &score_sources, &score_elements);
  }
  fbb.Finish(wire::CreatePointContextBlob(
                 fbb, scene_offset, context.emitters, context.rays_per_point,
                 context.rays_per_light, outgoing, corners, bounced, context.second_reach,
                 context.scoring.elements.empty() ? 0.0 : context.scoring.tolerance, score_sources,
                 score_elements),
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
  RADFARM_RETURN_IF_ERROR(ReadScoring(*root, &context.scoring));
  return out;
}

}  // namespace radfarm::codec
