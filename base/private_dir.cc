#include "base/private_dir.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace radfarm {

Status CreatePrivateDirectories(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path made;
  for (const fs::path& part : fs::path(path)) {
    made /= part;
    if (mkdir(made.c_str(), 0700) == 0) {
      // mkdir's mode is masked by the umask; chmod's is not.
      if (chmod(made.c_str(), 0700) != 0) {
        return Error{made.string() + ": cannot make it private: " + std::strerror(errno)};
      }
    } else if (errno != EEXIST) {
      return Error{made.string() + ": cannot create: " + std::strerror(errno)};
    }
  }
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return Error{path + ": cannot create: not a directory"};
  return Ok{};
}

}  // namespace radfarm
