#include "tests/architecture/include_rules.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>

namespace radfarm::architecture {
namespace {

constexpr std::string_view kBegin = "<!-- deps:begin -->";
constexpr std::string_view kEnd = "<!-- deps:end -->";

std::string Trim(std::string_view s) {
  const size_t begin = s.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return "";
  const size_t end = s.find_last_not_of(" \t\r");
  return std::string(s.substr(begin, end - begin + 1));
}

// "`daemon/store/`" -> "daemon/store".
std::string FolderName(std::string_view cell) {
  std::string name = Trim(cell);
  if (name.size() >= 2 && name.front() == '`' && name.back() == '`') {
    name = name.substr(1, name.size() - 2);
  }
  while (!name.empty() && name.back() == '/') name.pop_back();
  return name;
}

std::vector<std::string> Cells(std::string_view row) {
  std::vector<std::string> cells;
  std::string text = Trim(row);
  if (!text.empty() && text.front() == '|') text.erase(0, 1);
  if (!text.empty() && text.back() == '|') text.pop_back();
  std::stringstream in(text);
  std::string cell;
  while (std::getline(in, cell, '|')) cells.push_back(Trim(cell));
  return cells;
}

bool IsSeparator(const std::vector<std::string>& cells) {
  for (const std::string& cell : cells) {
    if (cell.empty() || cell.find_first_not_of("-: ") != std::string::npos) return false;
  }
  return true;
}

// The `quoted` folder names of a cell ("`base/`, `core/`" -> base, core); "—" or "" for none.
std::vector<std::string> QuotedFolders(const std::string& cell) {
  std::vector<std::string> folders;
  size_t pos = 0;
  while ((pos = cell.find('`', pos)) != std::string::npos) {
    const size_t end = cell.find('`', pos + 1);
    if (end == std::string::npos) break;
    folders.push_back(FolderName(cell.substr(pos, end - pos + 1)));
    pos = end + 1;
  }
  return folders;
}

bool StartsWithFolder(std::string_view path, std::string_view folder) {
  return path.size() > folder.size() && path.substr(0, folder.size()) == folder &&
         path[folder.size()] == '/';
}

bool IsCppFile(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  return ext == ".h" || ext == ".cc" || ext == ".hpp" || ext == ".cpp";
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::string Violation::Describe() const {
  return file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + message;
}

Result<DependencyTable> ParseDependencyTable(std::string_view markdown) {
  const size_t begin = markdown.find(kBegin);
  const size_t end = markdown.find(kEnd);
  if (begin == std::string_view::npos || end == std::string_view::npos || end < begin) {
    return Error{"no table between " + std::string(kBegin) + " and " + std::string(kEnd)};
  }
  std::stringstream lines(std::string(markdown.substr(begin + kBegin.size(), end - begin)));
  DependencyTable table;
  bool header_seen = false;
  std::string line;
  while (std::getline(lines, line)) {
    if (Trim(line).empty() || Trim(line).front() != '|') continue;
    const std::vector<std::string> cells = Cells(line);
    if (!header_seen) {  // | Folder | May include |
      header_seen = true;
      continue;
    }
    if (IsSeparator(cells)) continue;
    if (cells.size() != 2) return Error{"not a row of two cells: " + line};
    const std::string folder = FolderName(cells[0]);
    if (folder.empty()) return Error{"a row without a folder: " + line};
    if (table.contains(folder)) return Error{"folder '" + folder + "/' has two rows"};
    std::vector<std::string> allowed = QuotedFolders(cells[1]);
    table[folder] = std::set<std::string>(allowed.begin(), allowed.end());
  }
  if (table.empty()) return Error{"the dependency table has no rows"};
  for (const auto& [folder, allowed] : table) {
    for (const std::string& target : allowed) {
      if (!table.contains(target)) {
        return Error{"'" + folder + "/' may include '" + target + "/', which has no row"};
      }
    }
  }
  return table;
}

std::optional<std::string> FindCycle(const DependencyTable& table) {
  enum class Mark { kNone, kOnPath, kDone };
  std::map<std::string, Mark> marks;
  std::vector<std::string> path;
  std::optional<std::string> cycle;
  std::function<void(const std::string&)> visit = [&](const std::string& folder) {
    if (cycle) return;
    marks[folder] = Mark::kOnPath;
    path.push_back(folder);
    for (const std::string& next : table.at(folder)) {
      if (next == folder || cycle) continue;
      if (marks[next] == Mark::kOnPath) {
        std::string text;
        for (auto it = std::find(path.begin(), path.end(), next); it != path.end(); ++it) {
          text += *it + " -> ";
        }
        cycle = text + next;
        return;
      }
      if (marks[next] == Mark::kNone) visit(next);
    }
    path.pop_back();
    marks[folder] = Mark::kDone;
  };
  for (const auto& [folder, allowed] : table) {
    if (marks[folder] == Mark::kNone) visit(folder);
  }
  return cycle;
}

std::string FolderOf(const DependencyTable& table, std::string_view path) {
  std::string best;
  for (const auto& [folder, allowed] : table) {
    if (StartsWithFolder(path, folder) && folder.size() > best.size()) best = folder;
  }
  return best;
}

std::vector<Violation> CheckFile(const DependencyTable& table,
                                 const std::set<std::string>& project_folders,
                                 std::string_view path, std::string_view text) {
  static const std::regex kInclude(R"(^\s*#\s*include\s*"([^"]+)\")");
  std::vector<Violation> violations;
  const std::string file(path);
  const std::string from = FolderOf(table, path);
  if (from.empty()) {
    violations.push_back(
        {file, 0, "its folder has no row in docs/ARCHITECTURE.md's dependency table"});
    return violations;
  }
  std::stringstream lines{std::string(text)};
  std::string line;
  uint32_t number = 0;
  while (std::getline(lines, line)) {
    ++number;
    std::smatch match;
    if (!std::regex_search(line, match, kInclude)) continue;
    const std::string include = match[1];
    const size_t slash = include.find('/');
    if (slash == std::string::npos || !project_folders.contains(include.substr(0, slash))) continue;
    const std::string to = FolderOf(table, include);
    const std::string quoted = "(#include \"" + include + "\")";
    if (to.empty()) {
      violations.push_back({file, number, "includes a folder with no row in the table " + quoted});
    } else if (to != from && !table.at(from).contains(to)) {
      violations.push_back({file, number, from + "/ may not include " + to + "/ " + quoted});
    }
  }
  return violations;
}

std::vector<Violation> CheckTree(const DependencyTable& table, const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  std::set<std::string> project_folders;
  for (const auto& [folder, allowed] : table)
    project_folders.insert(folder.substr(0, folder.find('/')));
  std::vector<fs::path> top;
  for (const fs::directory_entry& entry : fs::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || name.starts_with(".") || name.starts_with("build")) continue;
    top.push_back(entry.path());
    project_folders.insert(name);
  }
  std::vector<std::string> files;
  for (const fs::path& dir : top) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir)) {
      if (entry.is_regular_file() && IsCppFile(entry.path())) {
        files.push_back(fs::relative(entry.path(), root).generic_string());
      }
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<Violation> violations;
  for (const std::string& file : files) {
    for (Violation& v : CheckFile(table, project_folders, file, ReadFile(root / file))) {
      violations.push_back(std::move(v));
    }
  }
  return violations;
}

}  // namespace radfarm::architecture
