#include "codec/punctual_light_codec.h"

#include <string>
#include <utility>
#include <vector>

#include "codec/decode_checks.h"

namespace radfarm::codec {
namespace {

// Far more than any scene a person lights by hand; the bound keeps a hostile blob small.
constexpr uint32_t kMaxLights = 1u << 20;
// As an IES file may hold (input/ies_file.cc), and the table's candela at most 10^6.
constexpr uint32_t kMaxAngles = 10000;
constexpr uint32_t kMaxCandela = 1000000;

wire::LightVector ToWire(const Vec3& v) { return {v.x, v.y, v.z}; }
wire::LightColour ToWire(const Rgb& c) { return {c.r, c.g, c.b}; }
Vec3 FromWire(const wire::LightVector* v) { return v ? Vec3{v->x(), v->y(), v->z()} : Vec3{}; }
Rgb FromWire(const wire::LightColour* c) { return c ? Rgb{c->r(), c->g(), c->b()} : Rgb{}; }

std::vector<double> FromWire(const flatbuffers::Vector<double>* v) {
  return v ? std::vector<double>(v->begin(), v->end()) : std::vector<double>{};
}

flatbuffers::Offset<wire::WireLight> EncodeLight(flatbuffers::FlatBufferBuilder& fbb,
                                                 const PunctualLight& l) {
  const wire::LightVector position = ToWire(l.position), direction = ToWire(l.direction);
  const wire::LightColour intensity = ToWire(l.intensity);
  if (l.kind != PunctualKind::kPhotometric) {
    return wire::CreateWireLight(fbb, static_cast<uint8_t>(l.kind), &position, &direction,
                                 &intensity, l.range, l.inner_cone, l.outer_cone);
  }
  const wire::LightVector reference = ToWire(l.reference);
  const auto vertical = fbb.CreateVector(l.table->vertical);
  const auto horizontal = fbb.CreateVector(l.table->horizontal);
  const auto candela = fbb.CreateVector(l.table->candela);
  return wire::CreateWireLight(fbb, static_cast<uint8_t>(l.kind), &position, &direction, &intensity,
                               l.range, l.inner_cone, l.outer_cone, &reference, vertical,
                               horizontal, candela);
}

// A photometric lamp's table, its sizes bounded before it is copied.
Result<CandelaTable> DecodeTable(const wire::WireLight& in, std::string_view kind, uint32_t i) {
  const auto size = [](const flatbuffers::Vector<double>* v) { return v ? v->size() : 0u; };
  if (size(in.vertical()) > kMaxAngles || size(in.horizontal()) > kMaxAngles ||
      size(in.candela()) > kMaxCandela) {
    return FieldError(kind, "light " + std::to_string(i), "its candela table is too large");
  }
  return CandelaTable{FromWire(in.vertical()), FromWire(in.horizontal()), FromWire(in.candela())};
}

}  // namespace

flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<wire::WireLight>>> EncodeLights(
    flatbuffers::FlatBufferBuilder& fbb, const std::vector<PunctualLight>& lights) {
  if (lights.empty()) return 0;
  std::vector<flatbuffers::Offset<wire::WireLight>> out;
  out.reserve(lights.size());
  for (const PunctualLight& l : lights) out.push_back(EncodeLight(fbb, l));
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
    if (l.kind == PunctualKind::kPhotometric) {
      Result<CandelaTable> table = DecodeTable(in, kind, i);
      RADFARM_RETURN_IF_ERROR(table);
      // The table's own problems first: its lumens are computed only over a sound one.
      if (std::string problem = CandelaTableProblem(*table); !problem.empty()) {
        return FieldError(kind, "light " + std::to_string(i), problem);
      }
      const PunctualLight placed = MakePhotometricLight(
          l.position, l.direction, FromWire(in.reference()), l.intensity, std::move(*table));
      l.reference = placed.reference;
      l.table = placed.table;
      l.table_lumens = placed.table_lumens;
    }
    const std::string problem = PunctualLightProblem(l);
    if (!problem.empty()) return FieldError(kind, "light " + std::to_string(i), problem);
    out.push_back(l);
  }
  return out;
}

}  // namespace radfarm::codec
