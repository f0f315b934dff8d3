#include "base/diagnostic.h"

namespace radfarm {

std::string Location(std::string_view file, uint32_t line) {
  std::string text(file);
  if (line > 0) text += ":" + std::to_string(line);
  return text;
}

Error ErrorAt(std::string_view file, uint32_t line, std::string_view what) {
  return Error{Location(file, line) + ": " + std::string(what)};
}

std::string WarningAt(std::string_view file, uint32_t line, std::string_view what) {
  return Location(file, line) + ": warning: " + std::string(what);
}

}  // namespace radfarm
