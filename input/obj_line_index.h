// A pass over an OBJ's text, made before tinyobjloader reads it, that records where statements are
// and rejects what tinyobjloader would misread without a word: it parses a malformed number as 0,
// ignores unknown statements, drops faces with fewer than 3 corners, keeps a face's corner count in
// an unsigned char, and reports out-of-range indices without a line. This is a validator and
// locator, not a second parser: the scene's coordinates and indices come from tinyobjloader.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace radfarm {

struct ObjFaceRecord {
  uint32_t line = 0;     // 1-based line of the `f` statement
  uint32_t corners = 0;  // number of vertices it names
};

struct ObjNamedLine {
  std::string name;
  uint32_t line = 0;
};

struct ObjLineIndex {
  uint32_t vertex_count = 0;                     // `v` statements
  std::vector<ObjFaceRecord> faces;              // every `f`, in file order
  std::vector<ObjNamedLine> material_libraries;  // every file named by `mtllib`
  std::vector<ObjNamedLine> material_uses;       // every `usemtl`
  std::vector<std::string> warnings;             // already prefixed with the file name
};

// Indexes and validates `text`, the contents of the OBJ at `path` with comments blanked
// (BlankComments). Errors are "path:line: what".
Result<ObjLineIndex> IndexObjLines(const std::string& path, std::string_view text);

}  // namespace radfarm
