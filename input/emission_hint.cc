#include "input/emission_hint.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>

namespace radfarm {
namespace {

// At most this many materials are named; a scene with fifty grey Blender materials gets a count.
constexpr size_t kMaxNamed = 3;

std::string Place(const DarkMaterial& m, uint32_t line) {
  return m.mtl_path.empty() ? "" : " (" + m.mtl_path + ":" + std::to_string(line) + ")";
}

std::string NameList(const std::vector<const DarkMaterial*>& found, bool ka_line) {
  std::string list;
  for (size_t i = 0; i < found.size() && i < kMaxNamed; ++i) {
    if (i > 0) list += ", ";
    const DarkMaterial& m = *found[i];
    list += "'" + m.name + "'" + Place(m, ka_line && m.ka_line > 0 ? m.ka_line : m.newmtl_line);
  }
  if (found.size() > kMaxNamed)
    list += " and " + std::to_string(found.size() - kMaxNamed) + " more";
  return list;
}

}  // namespace

bool LooksEmissive(const std::string& name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static constexpr std::array<std::string_view, 8> kWords = {"lamp", "light", "emissi",    "emit",
                                                             "glow", "bulb",  "luminaire", "neon"};
  return std::any_of(kWords.begin(), kWords.end(),
                     [&](std::string_view w) { return lower.find(w) != std::string::npos; });
}

std::string EmissionHint(const std::vector<DarkMaterial>& materials) {
  std::vector<const DarkMaterial*> named, ambient;
  for (const DarkMaterial& m : materials) {
    if (m.mtl_path.empty()) continue;  // the default grey of faces without a material
    if (LooksEmissive(m.name)) named.push_back(&m);
    if (m.ambient.Max() > 0) ambient.push_back(&m);
  }
  const std::string what_to_do =
      ": radfarm reads emission from Ke only, and Blender exports an Emission shader node as Ke 0 "
      "(use a Principled BSDF's Emission, or set Ke in the MTL)";
  if (!named.empty()) {
    return std::string(named.size() == 1 ? "; material " : "; materials ") +
           NameList(named, false) +
           (named.size() == 1 ? " looks like a light but has Ke 0"
                              : " look like lights but have Ke 0") +
           what_to_do;
  }
  if (!ambient.empty()) {
    return std::string(ambient.size() == 1 ? "; material " : "; materials ") +
           NameList(ambient, true) + " set" + (ambient.size() == 1 ? "s" : "") +
           " Ka (ambient) and Ke 0; if one should glow" + what_to_do;
  }
  return "";
}

}  // namespace radfarm
