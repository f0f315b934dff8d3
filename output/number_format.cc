#include "output/number_format.h"

#include <charconv>

namespace radfarm {

std::string FormatDouble(double value) {
  char buffer[64];
  // std::to_chars without a precision is the shortest exact round trip and ignores the locale.
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string FormatUnsigned(uint64_t value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace radfarm
