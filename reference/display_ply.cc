#include "reference/display_ply.h"

#include <cstring>
#include <fstream>
#include <sstream>

namespace radfarm::reference {
namespace {

constexpr const char* kVertexProperties[] = {
    "float x",    "float y",          "float z",          "uchar red",       "uchar green",
    "uchar blue", "float radiance_r", "float radiance_g", "float radiance_b"};

template <typename T>
bool Read(std::istream& in, T* value) {
  return bool(in.read(reinterpret_cast<char*>(value), sizeof(T)));
}

}  // namespace

Result<DisplayPly> ReadDisplayPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path + ": cannot open"};
  auto bad = [&](const std::string& what) { return Error{path + ": " + what}; };
  std::string line;
  size_t vertices = 0, faces = 0;
  size_t property = 0;
  bool in_vertex = false;
  while (std::getline(in, line)) {
    if (line == "end_header") break;
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format" && line != "format binary_little_endian 1.0") return bad("not binary LE");
    if (word == "element") {
      std::string kind;
      size_t n = 0;
      words >> kind >> n;
      in_vertex = kind == "vertex";
      (in_vertex ? vertices : faces) = n;
    } else if (word == "property" && in_vertex) {
      if (property >= 9 || line.substr(9) != kVertexProperties[property]) {
        return bad("unexpected vertex property '" + line + "'");
      }
      ++property;
    } else if (word == "property" && line != "property list uchar int vertex_indices") {
      return bad("unexpected face property '" + line + "'");
    }
  }
  if (property != 9) return bad("not the display PLY's vertex properties");
  DisplayPly ply;
  for (size_t v = 0; v < vertices; ++v) {
    float xyz[3], rad[3];
    unsigned char rgb[3];
    if (!Read(in, &xyz) || !Read(in, &rgb) || !Read(in, &rad)) return bad("truncated vertices");
    ply.positions.push_back({xyz[0], xyz[1], xyz[2]});
    ply.radiance.push_back({rad[0], rad[1], rad[2]});
  }
  for (size_t f = 0; f < faces; ++f) {
    unsigned char n = 0;
    if (!Read(in, &n)) return bad("truncated faces");
    std::vector<int32_t> idx(n);
    for (int32_t& i : idx) {
      if (!Read(in, &i)) return bad("truncated faces");
      if (i < 0 || size_t(i) >= vertices) return bad("vertex index out of range");
    }
    for (size_t k = 1; k + 1 < n; ++k) {
      ply.triangles.push_back({uint32_t(idx[0]), uint32_t(idx[k]), uint32_t(idx[k + 1])});
    }
  }
  return ply;
}

}  // namespace radfarm::reference
