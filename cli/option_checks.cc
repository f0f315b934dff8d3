#include "cli/option_checks.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
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
