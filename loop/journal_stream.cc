#include "loop/journal_stream.h"

#include <sys/stat.h>

#include <charconv>
#include <cstdint>
#include <string_view>

namespace radfarm::loop {
namespace {

bool ParseUnsigned(std::string_view text, uintmax_t* value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, *value);
  return !text.empty() && error == std::errc() && stop == end;
}

}  // namespace

bool FdIsJournalStream(int fd, const char* journal_stream) {
  if (journal_stream == nullptr) return false;
  const std::string_view value(journal_stream);
  const size_t colon = value.find(':');
  uintmax_t device = 0, inode = 0;
  if (colon == std::string_view::npos || !ParseUnsigned(value.substr(0, colon), &device) ||
      !ParseUnsigned(value.substr(colon + 1), &inode)) {
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) return false;
  return uintmax_t(st.st_dev) == device && uintmax_t(st.st_ino) == inode;
}

}  // namespace radfarm::loop
