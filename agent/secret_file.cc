#include "agent/secret_file.h"

#include <fcntl.h>
#include <string.h>  // explicit_bzero
#include <unistd.h>

#include <cerrno>
#include <vector>

#include "base/unique_fd.h"

namespace radfarm::agent {
namespace {

// Hex of the largest secret, with room for whitespace and a newline.
constexpr size_t kMaxFileBytes = 4 * 1024;

// Wipes the bytes read from the key file when it goes out of scope.
struct WipedBuffer {
  std::vector<char> bytes = std::vector<char>(kMaxFileBytes + 1);
  ~WipedBuffer() { explicit_bzero(bytes.data(), bytes.size()); }
};

}  // namespace

Result<protocol::FarmSecret> ReadSecretFile(const std::string& path) {
  UniqueFd fd(open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd.valid()) {
    return Error{path + ": cannot read the farm secret: " + std::string(strerror(errno))};
  }
  WipedBuffer buffer;
  size_t size = 0;
  for (;;) {
    const ssize_t n = read(fd.get(), buffer.bytes.data() + size, buffer.bytes.size() - size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return Error{path + ": cannot read the farm secret: " + strerror(errno)};
    if (n == 0) break;
    size += static_cast<size_t>(n);
    if (size > kMaxFileBytes) {
      return Error{path + ": not a farm secret: larger than " + std::to_string(kMaxFileBytes) +
                   " bytes"};
    }
  }
  Result<protocol::FarmSecret> secret =
      protocol::FarmSecret::FromHex(std::string_view(buffer.bytes.data(), size));
  if (!secret) return Error{path + ": not a farm secret: " + secret.error()};
  return secret;
}

}  // namespace radfarm::agent
