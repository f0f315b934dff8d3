// Small checks shared by the decoders: every decode error names the blob kind and the field.
#pragma once

#include <flatbuffers/flatbuffers.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm::codec {

// Largest blob any decoder accepts (FlatBuffers' own limit is 2 GiB).
inline constexpr size_t kMaxBlobBytes = size_t{1} << 30;

// Fails unless the blob is 8..kMaxBlobBytes long and carries `identifier` at bytes 4..7.
Status CheckBlobHeader(std::span<const uint8_t> blob, std::string_view kind,
                       const char* identifier);

// `blob` itself when 8 divides its address, else a copy of it kept in `*copy`: the Verifier needs
// aligned data; a std::vector's buffer is, a span into a frame may not be.
std::span<const uint8_t> Aligned(std::span<const uint8_t> blob, std::vector<uint8_t>* copy);

// The root table of a blob of `kind` once CheckBlobHeader and the FlatBuffers verifier
// (`verify`, the schema's VerifyXBuffer) passed. The root points into `blob`, or into `*aligned`
// where Aligned copied it: both must outlive its use.
template <typename Root>
Result<const Root*> VerifiedRoot(std::span<const uint8_t> blob, std::string_view kind,
                                 const char* identifier, bool (*verify)(flatbuffers::Verifier&),
                                 std::vector<uint8_t>* aligned,
                                 const flatbuffers::Verifier::Options& options = {}) {
  RADFARM_RETURN_IF_ERROR(CheckBlobHeader(blob, kind, identifier));
  blob = Aligned(blob, aligned);
  flatbuffers::Verifier verifier(blob.data(), blob.size(), options);
  if (!verify(verifier)) {
    return Error{std::string(kind) + ": not a valid FlatBuffer (verification failed)"};
  }
  return flatbuffers::GetRoot<Root>(blob.data());
}

using radfarm::IsFinite;  // Vec3 (core/vec3.h)
inline bool IsFinite(const Rgb& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}
// Each channel in [0, 1): the physically meaningful reflectances (input/material_check.h).
bool IsReflectance(const Rgb& c);
// Each channel finite and >= 0.
bool IsNonNegative(const Rgb& c);

// Element i of a FlatBuffers vector of structs, copied out byte for byte. The verifier checks only
// that a vector's length field is 4-byte aligned, so a crafted blob can place structs of doubles
// where 8 does not divide the address; reading them through the vector's pointers is undefined
// behaviour (UBSan: "member call on misaligned address"), a copy is not.
template <typename Struct>
Struct StructAt(const flatbuffers::Vector<const Struct*>& in, flatbuffers::uoffset_t i) {
  Struct out;
  std::memcpy(static_cast<void*>(&out), in.Data() + size_t{i} * sizeof(Struct), sizeof(Struct));
  return out;
}

// Element i of a FlatBuffers vector of 8-byte scalars (doubles), copied for the same reason.
template <typename Scalar>
Scalar ScalarAt(const flatbuffers::Vector<Scalar>& in, flatbuffers::uoffset_t i) {
  Scalar out;
  std::memcpy(&out, in.Data() + size_t{i} * sizeof(Scalar), sizeof(Scalar));
  return flatbuffers::EndianScalar(out);
}

Error FieldError(std::string_view kind, const std::string& field, std::string_view what);

}  // namespace radfarm::codec
