#include "base/text_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/diagnostic.h"
#include "base/unique_fd.h"

namespace radfarm {

namespace {

const char* FileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "not a regular file (a FIFO)";
  if (S_ISCHR(mode)) return "not a regular file (a character device)";
  if (S_ISBLK(mode)) return "not a regular file (a block device)";
  if (S_ISSOCK(mode)) return "not a regular file (a socket)";
  return "not a regular file";
}

}  // namespace

int OpenForReading(const std::string& path) {
  // O_NONBLOCK: opening a FIFO with no writer would wait for one forever. It changes nothing for
  // the regular files read after.
  return ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
}

Result<std::string> ReadTextFile(const std::string& path, uint64_t max_bytes) {
  UniqueFd fd(OpenForReading(path));
  if (!fd.valid()) return Error{path + ": cannot open: " + std::strerror(errno)};
  return ReadOpenFile(fd.get(), path, max_bytes);
}

Result<std::string> ReadOpenFile(int fd, const std::string& path, uint64_t max_bytes) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) return Error{path + ": cannot stat: " + std::strerror(errno)};
  if (!S_ISREG(st.st_mode)) return Error{path + ": cannot open: " + FileKind(st.st_mode)};
  const uint64_t size = static_cast<uint64_t>(st.st_size);
  if (size > max_bytes) {
    return Error{path + ": the file is " + std::to_string(size) + " bytes, over the limit of " +
                 std::to_string(max_bytes) + " bytes"};
  }
  std::string bytes(size, '\0');
  size_t have = 0;
  while (true) {
    if (have == bytes.size()) {
      // The file may have grown since fstat: read on, within the limit.
      if (bytes.size() >= max_bytes) {
        char probe;
        const ssize_t more = ::read(fd, &probe, 1);
        if (more > 0) {
          return Error{path + ": the file grew past the limit of " + std::to_string(max_bytes) +
                       " bytes while it was read"};
        }
        break;
      }
      bytes.resize(std::min<uint64_t>(max_bytes, bytes.size() + 65536));
    }
    const ssize_t got = ::read(fd, bytes.data() + have, bytes.size() - have);
    if (got < 0) {
      if (errno == EINTR) continue;
      return Error{path + ": cannot read: " + std::strerror(errno)};
    }
    if (got == 0) break;
    have += static_cast<size_t>(got);
  }
  bytes.resize(have);
  return bytes;
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
