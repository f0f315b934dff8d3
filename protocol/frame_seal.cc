#include "protocol/frame_seal.h"

#include <sodium.h>

#include <cstdlib>
#include <cstring>
#include <string_view>
#include <utility>

#include "protocol/frame_codec.h"
#include "protocol/handshake_auth.h"

namespace radfarm::protocol {
namespace {

constexpr char kAgentToMasterLabel[] = "radfarm agent to master key";  // sizeof includes the NUL
constexpr char kMasterToAgentLabel[] = "radfarm master to agent key";

static_assert(kSealKeyBytes == crypto_aead_chacha20poly1305_ietf_KEYBYTES);
static_assert(kSealTagBytes == crypto_aead_chacha20poly1305_ietf_ABYTES);
static_assert(kTagBytes == kSealKeyBytes, "a transcript MAC is used as a key");

using AeadNonce = std::array<uint8_t, crypto_aead_chacha20poly1305_ietf_NPUBBYTES>;

// 4 zero bytes, then the counter little-endian.
AeadNonce NonceOf(uint64_t counter) {
  AeadNonce nonce{};
  for (size_t i = 0; i < 8; ++i) nonce[4 + i] = static_cast<uint8_t>(counter >> (8 * i));
  return nonce;
}

std::array<uint8_t, kLengthPrefixBytes> LengthPrefix(size_t length) {
  std::array<uint8_t, kLengthPrefixBytes> prefix{};
  for (size_t i = 0; i < kLengthPrefixBytes; ++i)
    prefix[i] = static_cast<uint8_t>(length >> (8 * i));
  return prefix;
}

Error Unauthentic(uint64_t counter) {
  return Error{"frame failed authentication (frame " + std::to_string(counter) +
               " after the handshake): modified, dropped, reordered, replayed or injected on the "
               "way"};
}

}  // namespace

SealMode SealModeFromEnvironment() {
  static const SealMode mode = [] {
    const char* value = std::getenv("RADFARM_WIRE_SEAL");
    return value != nullptr && std::string_view(value) == "authenticate-only"
               ? SealMode::kAuthenticateOnly
               : SealMode::kEncrypt;
  }();
  return mode;
}

SessionKeys::~SessionKeys() {
  sodium_memzero(agent_to_master.data(), agent_to_master.size());
  sodium_memzero(master_to_agent.data(), master_to_agent.size());
}

SessionKeys DeriveSessionKeys(const FarmSecret& secret, const HelloMsg& hello,
                              const ChallengeMsg& challenge) {
  SessionKeys keys;
  keys.agent_to_master =
      TranscriptMac(secret, kAgentToMasterLabel, sizeof(kAgentToMasterLabel), hello, challenge);
  keys.master_to_agent =
      TranscriptMac(secret, kMasterToAgentLabel, sizeof(kMasterToAgentLabel), hello, challenge);
  return keys;
}

FrameSeal::FrameSeal(const std::array<uint8_t, kSealKeyBytes>& key, SealMode mode)
    : key_(key), mode_(mode) {}

FrameSeal::~FrameSeal() { sodium_memzero(key_.data(), key_.size()); }

FrameSeal::FrameSeal(FrameSeal&& other) noexcept
    : key_(other.key_), mode_(other.mode_), counter_(other.counter_) {
  sodium_memzero(other.key_.data(), other.key_.size());
}

FrameSeal& FrameSeal::operator=(FrameSeal&& other) noexcept {
  if (this != &other) {
    key_ = other.key_;
    mode_ = other.mode_;
    counter_ = other.counter_;
    sodium_memzero(other.key_.data(), other.key_.size());
  }
  return *this;
}

std::vector<uint8_t> FrameSeal::Seal(std::span<const uint8_t> frame) {
  const std::span<const uint8_t> body = frame.subspan(kLengthPrefixBytes);
  const size_t sealed_length = body.size() + kSealTagBytes;
  std::vector<uint8_t> out(kLengthPrefixBytes + sealed_length);
  const auto prefix = LengthPrefix(sealed_length);
  std::memcpy(out.data(), prefix.data(), prefix.size());
  const AeadNonce nonce = NonceOf(counter_++);
  uint8_t* sealed = out.data() + kLengthPrefixBytes;
  if (mode_ == SealMode::kEncrypt) {
    crypto_aead_chacha20poly1305_ietf_encrypt(sealed, nullptr, body.data(), body.size(),
                                              prefix.data(), prefix.size(), nullptr, nonce.data(),
                                              key_.data());
  } else {
    // The clear body, then a tag over prefix and body.
    // (An empty message still needs valid pointers: libsodium declares them nonnull.)
    std::memcpy(sealed, body.data(), body.size());
    crypto_aead_chacha20poly1305_ietf_encrypt_detached(
        sealed, sealed + body.size(), nullptr, sealed, 0, out.data(),
        kLengthPrefixBytes + body.size(), nullptr, nonce.data(), key_.data());
  }
  return out;
}

Result<std::vector<uint8_t>> FrameSeal::Open(std::span<const uint8_t> body) {
  const uint64_t counter = counter_;
  if (body.size() < kSealTagBytes) return Unauthentic(counter);
  const size_t plain_size = body.size() - kSealTagBytes;
  const auto prefix = LengthPrefix(body.size());
  const AeadNonce nonce = NonceOf(counter);
  std::vector<uint8_t> plain(plain_size);
  int failed = 0;
  if (mode_ == SealMode::kEncrypt) {
    failed = crypto_aead_chacha20poly1305_ietf_decrypt(plain.data(), nullptr, nullptr, body.data(),
                                                       body.size(), prefix.data(), prefix.size(),
                                                       nonce.data(), key_.data());
  } else {
    std::vector<uint8_t> authenticated(prefix.begin(), prefix.end());
    authenticated.insert(authenticated.end(), body.begin(), body.begin() + plain_size);
    uint8_t none = 0;  // the empty message's place
    failed = crypto_aead_chacha20poly1305_ietf_decrypt_detached(
        &none, nullptr, &none, 0, body.data() + plain_size, authenticated.data(),
        authenticated.size(), nonce.data(), key_.data());
    if (failed == 0) std::memcpy(plain.data(), body.data(), plain_size);
  }
  if (failed != 0) return Unauthentic(counter);
  ++counter_;
  return plain;
}

}  // namespace radfarm::protocol
