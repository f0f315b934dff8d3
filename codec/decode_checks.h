// Small checks shared by the decoders: every decode error names the blob kind and the field.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "base/result.h"
#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm::codec {

// Largest blob any decoder accepts (FlatBuffers' own limit is 2 GiB).
inline constexpr size_t kMaxBlobBytes = size_t{1} << 30;

// Fails unless the blob is 8..kMaxBlobBytes long and carries `identifier` at bytes 4..7.
Status CheckBlobHeader(std::span<const uint8_t> blob, std::string_view kind,
                       const char* identifier);

using radfarm::IsFinite;  // Vec3 (core/vec3.h)
inline bool IsFinite(const Rgb& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}
// Each channel in [0, 1): the physically meaningful reflectances (input/material_check.h).
bool IsReflectance(const Rgb& c);
// Each channel finite and >= 0.
bool IsNonNegative(const Rgb& c);

Error FieldError(std::string_view kind, const std::string& field, std::string_view what);

}  // namespace radfarm::codec
