#include "codec/sky_codec.h"

#include <string>

#include "codec/decode_checks.h"

namespace radfarm::codec {

flatbuffers::Offset<wire::WireSky> EncodeSky(flatbuffers::FlatBufferBuilder& fbb, const Sky& sky) {
  if (sky.kind == SkyKind::kNone) return 0;
  const wire::SkyVector sun{sky.sun.x, sky.sun.y, sky.sun.z};
  return wire::CreateWireSky(fbb, static_cast<uint8_t>(sky.kind), sky.zenith, &sun);
}

Result<Sky> DecodeSky(const wire::WireSky* in, std::string_view kind) {
  Sky sky;
  if (in == nullptr) return sky;
  sky.kind = static_cast<SkyKind>(in->kind());
  sky.zenith = in->zenith();
  if (const wire::SkyVector* sun = in->sun()) sky.sun = {sun->x(), sun->y(), sun->z()};
  // Written only for a sky, so an empty one on the wire was not written by an encoder.
  if (sky.kind == SkyKind::kNone) return FieldError(kind, "sky", "has no kind");
  if (const std::string problem = SkyProblem(sky); !problem.empty()) {
    return FieldError(kind, "sky", problem);
  }
  return sky;
}

}  // namespace radfarm::codec
