#include "input/obj_line_index.h"

#include <algorithm>
#include <iterator>
#include <set>

#include "base/diagnostic.h"
#include "base/result.h"
#include "base/text_file.h"

namespace radfarm {
namespace {

// tinyobjloader stores a face's corner count in an unsigned char.
constexpr uint32_t kMaxCorners = 255;

// Statements of the OBJ specification that describe nothing a radiosity scene can use (curves,
// surfaces, lines, points, display attributes): skipped with one warning each.
constexpr std::string_view kIgnoredStatements[] = {
    "vp",    "l",     "p",        "cstype",   "deg",    "bmat",       "step",      "curv",
    "curv2", "surf",  "parm",     "trim",     "hole",   "scrv",       "sp",        "end",
    "con",   "mg",    "lod",      "usemap",   "maplib", "shadow_obj", "trace_obj", "ctech",
    "stech", "bevel", "c_interp", "d_interp", "call",   "csh"};

bool IsIgnoredStatement(std::string_view keyword) {
  return std::find(std::begin(kIgnoredStatements), std::end(kIgnoredStatements), keyword) !=
         std::end(kIgnoredStatements);
}

class ObjIndexer {
 public:
  explicit ObjIndexer(const std::string& path) : path_(path) {}

  Status Statement(uint32_t line, const std::vector<std::string_view>& words);
  Status CheckForwardIndices() const;
  ObjLineIndex Take() { return std::move(index_); }

 private:
  Status Numbers(uint32_t line, const std::vector<std::string_view>& words, size_t min,
                 size_t max) {
    return CheckNumberWords(path_, line, words, min, max);
  }
  Status Face(uint32_t line, const std::vector<std::string_view>& words);
  Status Corner(uint32_t line, std::string_view corner, long long* vertex);
  Error Fail(uint32_t line, const std::string& what) const { return ErrorAt(path_, line, what); }

  const std::string& path_;
  ObjLineIndex index_;
  std::set<std::string, std::less<>> warned_statements_;
  // Largest positive vertex index of each face, checked once the vertex count is known because
  // positive indices may name vertices defined later in the file.
  std::vector<std::pair<uint32_t, long long>> largest_index_;
};

Status ObjIndexer::Statement(uint32_t line, const std::vector<std::string_view>& words) {
  const std::string_view keyword = words[0];
  if (keyword == "v") {
    ++index_.vertex_count;
    // x y z, optionally w or an r g b colour, which tinyobjloader reads and we ignore.
    return Numbers(line, words, 3, 7);
  }
  if (keyword == "vt") return Numbers(line, words, 1, 3);
  if (keyword == "vn") return Numbers(line, words, 3, 3);
  if (keyword == "f") return Face(line, words);
  if (keyword == "usemtl") {
    if (words.size() != 2) return Fail(line, "'usemtl' needs exactly one material name");
    index_.material_uses.push_back({std::string(words[1]), line});
    return Ok{};
  }
  if (keyword == "mtllib") {
    if (words.size() < 2) return Fail(line, "'mtllib' needs a file name");
    for (size_t i = 1; i < words.size(); ++i) {
      index_.material_libraries.push_back({std::string(words[i]), line});
    }
    return Ok{};
  }
  if (keyword == "g" || keyword == "o" || keyword == "s") return Ok{};
  if (IsIgnoredStatement(keyword)) {
    if (warned_statements_.emplace(keyword).second) {
      index_.warnings.push_back(WarningAt(
          path_, line, "ignoring '" + std::string(keyword) + "' statements (not surfaces)"));
    }
    // tinyobjloader does read `l` and `p` and fails on a zero index: validate those corners too.
    if (keyword == "l" || keyword == "p") {
      long long vertex = 0;
      for (size_t i = 1; i < words.size(); ++i) {
        RADFARM_RETURN_IF_ERROR(Corner(line, words[i], &vertex));
      }
    }
    return Ok{};
  }
  return Fail(line, "unknown statement '" + std::string(keyword) + "'");
}

Status ObjIndexer::Face(uint32_t line, const std::vector<std::string_view>& words) {
  const uint32_t corners = static_cast<uint32_t>(words.size() - 1);
  if (corners < 3) {
    return Fail(line, "face has " + std::to_string(corners) + " vertices (at least 3 needed)");
  }
  if (corners > kMaxCorners) {
    return Fail(line, "face has " + std::to_string(corners) + " vertices (at most " +
                          std::to_string(kMaxCorners) + " supported)");
  }
  long long largest = 0;
  for (size_t i = 1; i < words.size(); ++i) {
    long long vertex = 0;
    RADFARM_RETURN_IF_ERROR(Corner(line, words[i], &vertex));
    if (vertex < 0 && -vertex > static_cast<long long>(index_.vertex_count)) {
      return Fail(line, "vertex index " + std::to_string(vertex) + " out of range (" +
                            std::to_string(index_.vertex_count) + " vertices before this line)");
    }
    if (vertex > largest) largest = vertex;
  }
  index_.faces.push_back({line, corners});
  largest_index_.emplace_back(line, largest);
  return Ok{};
}

// A corner is v, v/t, v//n or v/t/n: nonzero integers, negative ones counting back from the last.
Status ObjIndexer::Corner(uint32_t line, std::string_view corner, long long* vertex) {
  const std::string text(corner);
  std::vector<std::string_view> parts;
  size_t start = 0;
  while (true) {
    size_t slash = corner.find('/', start);
    parts.push_back(corner.substr(start, slash == std::string_view::npos ? slash : slash - start));
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  const bool empty_texture_allowed = parts.size() == 3;
  if (parts.size() > 3) return Fail(line, "malformed vertex reference '" + text + "'");
  for (size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].empty() && i == 1 && empty_texture_allowed) continue;
    long long value = 0;
    if (!ParseInt(parts[i], &value)) {
      return Fail(line, "malformed vertex reference '" + text + "'");
    }
    if (value == 0) {
      return Fail(line, "index 0 in '" + text + "' (OBJ indices start at 1)");
    }
    if (i == 0) *vertex = value;
  }
  return Ok{};
}

Status ObjIndexer::CheckForwardIndices() const {
  for (const auto& [line, largest] : largest_index_) {
    if (largest > static_cast<long long>(index_.vertex_count)) {
      return Fail(line, "vertex index " + std::to_string(largest) + " out of range (" +
                            std::to_string(index_.vertex_count) + " vertices)");
    }
  }
  return Ok{};
}

}  // namespace

Result<ObjLineIndex> IndexObjLines(const std::string& path, std::string_view text) {
  ObjIndexer indexer(path);
  const std::vector<std::string_view> lines = SplitLines(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::vector<std::string_view> words = SplitWords(lines[i]);
    if (words.empty()) continue;
    RADFARM_RETURN_IF_ERROR(indexer.Statement(static_cast<uint32_t>(i + 1), words));
  }
  RADFARM_RETURN_IF_ERROR(indexer.CheckForwardIndices());
  return indexer.Take();
}

}  // namespace radfarm
