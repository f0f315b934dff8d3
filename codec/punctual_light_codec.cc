#include "codec/punctual_light_codec.h"

#include <string>

#include "codec/decode_checks.h"

namespace radfarm::codec {
namespace {

// Far more than any scene a person lights by hand; the bound keeps a hostile blob small.
constexpr uint32_t kMaxLights = 1u << 20;

wire::LightVector ToWire(const Vec3& v) { return {v.x, v.y, v.z}; }
wire::LightColour ToWire(const Rgb& c) { return {c.r, c.g, c.b}; }
Vec3 FromWire(const wire::LightVector* v) { return v ? Vec3{v->x(), v->y(), v->z()} : Vec3{}; }
Rgb FromWire(const wire::LightColour* c) { return c ? Rgb{c->r(), c->g(), c->b()} : Rgb{}; }

}  // namespace

flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<wire::WireLight>>> EncodeLights(
    flatbuffers::FlatBufferBuilder& fbb, const std::vector<PunctualLight>& lights) {
  if (lights.empty()) return 0;
  std::vector<flatbuffers::Offset<wire::WireLight>> out;
  out.reserve(lights.size());
  for (const PunctualLight& l : lights) {
    const wire::LightVector position = ToWire(l.position), direction = ToWire(l.direction);
    const wire::LightColour intensity = ToWire(l.intensity);
    out.push_back(wire::CreateWireLight(fbb, static_cast<uint8_t>(l.kind), &position, &direction,
                                        &intensity, l.range, l.inner_cone, l.outer_cone));
  }
  return fbb.CreateVector(out);
}

Result<std::vector<PunctualLight>> DecodeLights(
    const flatbuffers::Vector<flatbuffers::Offset<wire::WireLight>>* lights,
    std::string_view kind) {
  std::vector<PunctualLight> out;
  if (lights == nullptr) return out;
  if (lights->size() > kMaxLights) return FieldError(kind, "lights", "too many");
  for (uint32_t i = 0; i < lights->size(); ++i) {
    const wire::WireLight& in = *lights->Get(i);
    PunctualLight l;
    l.kind = static_cast<PunctualKind>(in.kind());
    l.position = FromWire(in.position());
    l.direction = FromWire(in.direction());
    l.intensity = FromWire(in.intensity());
    l.range = in.range();
    l.inner_cone = in.inner_cone();
    l.outer_cone = in.outer_cone();
    const std::string problem = PunctualLightProblem(l);
    if (!problem.empty()) return FieldError(kind, "light " + std::to_string(i), problem);
    out.push_back(l);
  }
  return out;
}

}  // namespace radfarm::codec
