#include "cli/option_checks.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

namespace radfarm {

const CLI::Validator& PositiveInteger() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        int64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error != std::errc() || stop != end || value < 1) {
          return "'" + text + "' is not a positive integer";
        }
        return "";
      },
      "INTEGER >= 1");
  return check;
}

const CLI::Validator& UnsignedInteger() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || text[0] == '-' || error != std::errc() || stop != end) {
          return "'" + text + "' is not an integer from 0 to 18446744073709551615";
        }
        return "";
      },
      "INTEGER >= 0");
  return check;
}

const CLI::Validator& ByteSize() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        const std::string refused =
            "'" + text + "' is not a size in bytes from 1 to 18446744073709551615 (e.g. 8G, 512M)";
        uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || text[0] == '-' || error != std::errc() || value == 0) return refused;
        std::string unit(stop, end);
        for (char& c : unit) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (unit.size() == 3 && unit.substr(1) == "ib") unit.resize(1);
        if (unit.size() == 2 && unit[1] == 'b') unit.resize(1);
        const std::string units = "bkmgt";
        const size_t power = unit.empty() ? 0 : units.find(unit);
        if (unit.size() > 1 || power == std::string::npos) return refused;
        for (size_t i = 0; i < power; ++i) {
          if (value > std::numeric_limits<uint64_t>::max() / 1024) return refused;
          value *= 1024;
        }
        text = std::to_string(value);
        return "";
      },
      "SIZE");
  return check;
}

const CLI::Validator& PositiveId() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error != std::errc() || stop != end || value < 1) {
          return "'" + text + "' is not a job id (an integer from 1 to 18446744073709551615)";
        }
        return "";
      },
      "ID >= 1");
  return check;
}

const CLI::Validator& PositiveReal() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (text.empty() || *stop != '\0' || !std::isfinite(value) || value <= 0) {
          return "'" + text + "' is not a positive number";
        }
        return "";
      },
      "NUMBER > 0");
  return check;
}

CLI::Validator RealInRange(double low, double high) {
  const auto format = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return std::string(text);
  };
  const std::string range = "[" + format(low) + ", " + format(high) + "]";
  return CLI::Validator(
      [low, high, range](std::string& text) -> std::string {
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (text.empty() || *stop != '\0' || !(value >= low && value <= high)) {
          return "'" + text + "' is not a number in " + range;
        }
        return "";
      },
      "NUMBER in " + range);
}

CLI::Validator RealIn(const Interval& range) {
  return CLI::Validator(
      [range](std::string& text) -> std::string {
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (text.empty() || *stop != '\0') return "must be a number, got '" + text + "'";
        if (!range.Contains(value)) return "must be " + range.Describe() + ", got " + text;
        return "";
      },
      "NUMBER " + range.Describe());
}

}  // namespace radfarm
