// The include-dependency rules of docs/ARCHITECTURE.md: a table, between the markers
// "<!-- deps:begin -->" and "<!-- deps:end -->", of the folders and the folders each may include:
//
//   | Folder | May include |
//   | --- | --- |
//   | `base/` | — |
//   | `input/` | `base/`, `core/` |
//
// A folder may always include itself. A row may name a subfolder (`daemon/scheduler/`): a file
// belongs to the longest row its path starts with. Quoted includes whose first path component is
// not a folder of the tree ("toml++/toml.h", generated "frame_generated.h") are not checked.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace radfarm::architecture {

// Folder ("daemon/scheduler", no trailing slash) -> the folders it may include.
using DependencyTable = std::map<std::string, std::set<std::string>>;

// The table between the markers. Errors for a missing marker, a malformed or repeated row, or an
// allowed folder that has no row of its own.
Result<DependencyTable> ParseDependencyTable(std::string_view markdown);

// A cycle in the table ("a -> b -> a"), if there is one.
std::optional<std::string> FindCycle(const DependencyTable& table);

// The longest row `path` starts with ("daemon/store/x.h" -> "daemon/store"), or "" for none.
std::string FolderOf(const DependencyTable& table, std::string_view path);

// One problem, one line: "FILE:LINE: FROM/ may not include TO/ (#include \"...\")".
struct Violation {
  std::string file;
  uint32_t line = 0;
  std::string message;
  std::string Describe() const;
};

// The includes of one file (`path` relative to the tree's root, `text` its contents) that the
// table does not allow. `project_folders`: the tree's top-level folders; only includes starting
// with one of them are checked.
std::vector<Violation> CheckFile(const DependencyTable& table,
                                 const std::set<std::string>& project_folders,
                                 std::string_view path, std::string_view text);

// Every C++ file (.h, .cc, .hpp, .cpp) under `root`'s top-level folders, except build* and hidden
// ones: its includes, and whether its folder has a row at all.
std::vector<Violation> CheckTree(const DependencyTable& table, const std::filesystem::path& root);

}  // namespace radfarm::architecture
