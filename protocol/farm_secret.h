// The farm's shared secret: the HMAC key of the handshake. It never goes into a message; only
// tags computed with it do. Copies are wiped when destroyed.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace radfarm::protocol {

class FarmSecret {
 public:
  // kMinSecretBytes..kMaxSecretBytes bytes.
  static Result<FarmSecret> FromBytes(std::span<const uint8_t> bytes);
  // Hex digits, as in a key file; surrounding whitespace is ignored.
  static Result<FarmSecret> FromHex(std::string_view hex);
  // 32 fresh random bytes, for making a key file.
  static Result<FarmSecret> Generate();

  FarmSecret(const FarmSecret&) = default;
  FarmSecret(FarmSecret&&) = default;
  // Assignment wipes the key it replaces before its buffer is reused or freed; a moved-from
  // secret is empty.
  FarmSecret& operator=(const FarmSecret& other);
  FarmSecret& operator=(FarmSecret&& other) noexcept;
  ~FarmSecret();

  std::span<const uint8_t> bytes() const { return key_; }
  std::string ToHex() const;

 private:
  explicit FarmSecret(std::vector<uint8_t> key) : key_(std::move(key)) {}
  void Wipe();
  std::vector<uint8_t> key_;
};

}  // namespace radfarm::protocol
