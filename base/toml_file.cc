#include "base/toml_file.h"

#include "base/diagnostic.h"
#include "base/text_file.h"

namespace radfarm {
namespace {

// Job files and configurations are a few kilobytes; a larger one is a mistake (or /dev/zero).
constexpr uint64_t kMaxTomlFileBytes = 16u << 20;

}  // namespace

Result<toml::table> ParseToml(const std::string& path, const std::string& text) {
#if TOML_EXCEPTIONS
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const std::string what(e.description());
    return ErrorAt(path, e.source().begin.line, what.substr(0, what.find('\n')));
  }
#else
  toml::parse_result parsed = toml::parse(text, path);
  if (!parsed) {
    const std::string what(parsed.error().description());
    return ErrorAt(path, parsed.error().source().begin.line, what.substr(0, what.find('\n')));
  }
  return std::move(parsed).table();
#endif
}

Result<toml::table> ReadTomlFile(const std::string& path) {
  Result<std::string> text = ReadTextFile(path, kMaxTomlFileBytes);
  RADFARM_RETURN_IF_ERROR(text);
  return ParseToml(path, *text);
}

}  // namespace radfarm
