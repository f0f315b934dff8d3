#include "base/text_file.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/diagnostic.h"

namespace radfarm {

Result<std::string> ReadTextFile(const std::string& path) {
  std::error_code ec;
  // std::ifstream happily opens a directory on Linux and then reads nothing: refuse it up front.
  if (std::filesystem::is_directory(path, ec)) {
    return Error{path + ": cannot open: is a directory"};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path + ": cannot open: " + std::strerror(errno)};
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) return Error{path + ": cannot read: " + std::strerror(errno)};
  return bytes.str();
}

std::vector<std::string_view> SplitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find_first_of("\r\n", start);
    if (end == std::string_view::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end - start));
    start = end + ((text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ? 2 : 1);
  }
  return lines;
}

void BlankComments(std::string* text) {
  bool in_comment = false;
  for (char& c : *text) {
    if (c == '\n' || c == '\r') {
      in_comment = false;
    } else if (in_comment || c == '#') {
      in_comment = true;
      c = ' ';
    }
  }
}

std::vector<std::string_view> SplitWords(std::string_view line) {
  std::vector<std::string_view> words;
  size_t pos = 0;
  while (true) {
    pos = line.find_first_not_of(" \t", pos);
    if (pos == std::string_view::npos) break;
    size_t end = line.find_first_of(" \t", pos);
    if (end == std::string_view::npos) end = line.size();
    words.push_back(line.substr(pos, end - pos));
    pos = end;
  }
  return words;
}

namespace {

// std::from_chars rejects a leading '+', which OBJ exporters do write.
std::string_view WithoutPlus(std::string_view word) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-') word.remove_prefix(1);
  return word;
}

}  // namespace

bool ParseDouble(std::string_view word, double* value) {
  word = WithoutPlus(word);
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, *value);
  if (ptr != end) return false;
  if (ec == std::errc::result_out_of_range) {
    // A well-formed number beyond double's range: give the caller +-inf (or 0 for underflow), as
    // strtod does, so that "1e999" is reported as not finite rather than as not a number.
    *value = std::strtod(std::string(word).c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
}

bool ParseInt(std::string_view word, long long* value) {
  word = WithoutPlus(word);
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

Status CheckNumberWords(const std::string& path, uint32_t line,
                        const std::vector<std::string_view>& words, size_t min, size_t max) {
  const std::string keyword(words[0]);
  const size_t count = words.size() - 1;
  if (count < min || count > max) {
    const std::string expected =
        min == max ? std::to_string(min) : std::to_string(min) + " to " + std::to_string(max);
    return ErrorAt(
        path, line,
        "'" + keyword + "' needs " + expected + " numbers, got " + std::to_string(count));
  }
  for (size_t i = 1; i < words.size(); ++i) {
    const std::string word(words[i]);
    double value = 0;
    if (!ParseDouble(word, &value)) {
      return ErrorAt(path, line, "'" + keyword + "': cannot parse '" + word + "' as a number");
    }
    if (!std::isfinite(value)) {
      return ErrorAt(path, line, "'" + keyword + "': '" + word + "' is not a finite number");
    }
  }
  return Ok{};
}

}  // namespace radfarm
