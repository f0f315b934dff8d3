#include "protocol/farm_secret.h"

#include <sodium.h>

#include "base/result.h"
#include "protocol/handshake_auth.h"
#include "protocol/limits.h"

namespace radfarm::protocol {

Result<FarmSecret> FarmSecret::FromBytes(std::span<const uint8_t> bytes) {
  if (bytes.size() < kMinSecretBytes || bytes.size() > kMaxSecretBytes) {
    return Error{"farm secret: " + std::to_string(bytes.size()) + " bytes, need " +
                 std::to_string(kMinSecretBytes) + ".." + std::to_string(kMaxSecretBytes)};
  }
  return FarmSecret(std::vector<uint8_t>(bytes.begin(), bytes.end()));
}

Result<FarmSecret> FarmSecret::FromHex(std::string_view hex) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!hex.empty() && is_space(hex.front())) hex.remove_prefix(1);
  while (!hex.empty() && is_space(hex.back())) hex.remove_suffix(1);
  if (hex.size() % 2 != 0 || hex.size() / 2 > kMaxSecretBytes) {
    return Error{"farm secret: need an even number of hex digits, at most " +
                 std::to_string(2 * kMaxSecretBytes)};
  }
  std::vector<uint8_t> key(hex.size() / 2);
  size_t decoded = 0;
  const char* end = nullptr;
  if (sodium_hex2bin(key.data(), key.size(), hex.data(), hex.size(), nullptr, &decoded, &end) !=
          0 ||
      decoded != key.size()) {
    sodium_memzero(key.data(), key.size());
    return Error{"farm secret: not hex"};
  }
  Result<FarmSecret> secret = FromBytes(key);
  sodium_memzero(key.data(), key.size());
  return secret;
}

Result<FarmSecret> FarmSecret::Generate() {
  RADFARM_RETURN_IF_ERROR(InitSodium());
  std::vector<uint8_t> key(kMinSecretBytes);
  randombytes_buf(key.data(), key.size());
  return FarmSecret(std::move(key));
}

FarmSecret& FarmSecret::operator=(const FarmSecret& other) {
  if (this != &other) {
    Wipe();
    key_.assign(other.key_.begin(), other.key_.end());
  }
  return *this;
}

FarmSecret& FarmSecret::operator=(FarmSecret&& other) noexcept {
  if (this != &other) {
    Wipe();
    key_ = std::move(other.key_);
    other.key_.clear();
  }
  return *this;
}

FarmSecret::~FarmSecret() { Wipe(); }

void FarmSecret::Wipe() {
  if (!key_.empty()) sodium_memzero(key_.data(), key_.size());
}

std::string FarmSecret::ToHex() const {
  std::string hex(2 * key_.size() + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), key_.data(), key_.size());
  hex.pop_back();
  return hex;
}

}  // namespace radfarm::protocol
