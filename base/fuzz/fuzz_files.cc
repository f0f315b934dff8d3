#include "base/fuzz/fuzz_files.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace radfarm::fuzz {

std::vector<std::string_view> SplitFuzzInput(std::span<const uint8_t> data, size_t max_parts) {
  std::string_view rest(reinterpret_cast<const char*>(data.data()), data.size());
  std::vector<std::string_view> parts;
  while (parts.size() + 1 < max_parts) {
    const size_t at = rest.find(kFuzzPartSeparator);
    if (at == std::string_view::npos) break;
    parts.push_back(rest.substr(0, at));
    rest.remove_prefix(at + kFuzzPartSeparator.size());
  }
  parts.push_back(rest);
  return parts;
}

namespace {

std::filesystem::path MakeScratchDirectory() {
  std::error_code ec;
  const std::filesystem::path base = std::filesystem::is_directory("/dev/shm", ec)
                                         ? "/dev/shm"
                                         : std::filesystem::temp_directory_path();
  std::string pattern = (base / "radfarm-fuzz-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) std::abort();
  return pattern;
}

}  // namespace

const std::filesystem::path& FuzzScratchDirectory() {
  static const std::filesystem::path directory = MakeScratchDirectory();
  static const bool cleanup_registered = [] {
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(directory, ec);
    });
    return true;
  }();
  (void)cleanup_registered;
  return directory;
}

void WriteFuzzFile(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out.good()) std::abort();
}

}  // namespace radfarm::fuzz
