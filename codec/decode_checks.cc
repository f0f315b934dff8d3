#include "codec/decode_checks.h"

#include <cstring>

namespace radfarm::codec {

std::span<const uint8_t> Aligned(std::span<const uint8_t> blob, std::vector<uint8_t>* copy) {
  if (reinterpret_cast<uintptr_t>(blob.data()) % 8 == 0) return blob;
  copy->assign(blob.begin(), blob.end());
  return *copy;
}

Status CheckBlobHeader(std::span<const uint8_t> blob, std::string_view kind,
                       const char* identifier) {
  if (blob.size() < 8) {
    return Error{std::string(kind) + ": " + std::to_string(blob.size()) +
                 " bytes is too short to hold one"};
  }
  if (blob.size() > kMaxBlobBytes) {
    return Error{std::string(kind) + ": " + std::to_string(blob.size()) + " bytes is over the " +
                 std::to_string(kMaxBlobBytes) + "-byte limit"};
  }
  if (std::memcmp(blob.data() + 4, identifier, 4) != 0) {
    return Error{std::string(kind) + ": wrong file identifier (expected \"" + identifier + "\")"};
  }
  return Ok{};
}

bool IsReflectance(const Rgb& c) {
  const auto ok = [](double v) { return v >= 0 && v < 1; };  // false for NaN
  return ok(c.r) && ok(c.g) && ok(c.b);
}

bool IsNonNegative(const Rgb& c) { return IsFinite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0; }

Error FieldError(std::string_view kind, const std::string& field, std::string_view what) {
  return Error{std::string(kind) + ": " + field + " " + std::string(what)};
}

}  // namespace radfarm::codec
