#include "protocol/agent_key.h"

#include <sodium.h>

#include <array>

#include "protocol/handshake_auth.h"

namespace radfarm::protocol {
namespace {

constexpr char kAgentKeyLabel[] = "radfarm agent key";  // sizeof includes the NUL

template <typename T>
void AddLittleEndian(crypto_auth_hmacsha256_state& state, T value) {
  std::array<uint8_t, sizeof(T)> bytes;
  for (size_t i = 0; i < sizeof(T); ++i) bytes[i] = static_cast<uint8_t>(value >> (8 * i));
  crypto_auth_hmacsha256_update(&state, bytes.data(), bytes.size());
}

}  // namespace

FarmSecret DeriveAgentKey(const FarmSecret& farm_secret, std::string_view name,
                          uint64_t generation) {
  (void)InitSodium();  // HMAC needs no entropy: it cannot fail
  crypto_auth_hmacsha256_state state;
  crypto_auth_hmacsha256_init(&state, farm_secret.bytes().data(), farm_secret.bytes().size());
  crypto_auth_hmacsha256_update(&state, reinterpret_cast<const unsigned char*>(kAgentKeyLabel),
                                sizeof(kAgentKeyLabel));
  AddLittleEndian(state, static_cast<uint32_t>(name.size()));
  crypto_auth_hmacsha256_update(&state, reinterpret_cast<const unsigned char*>(name.data()),
                                name.size());
  AddLittleEndian(state, generation);
  std::array<uint8_t, crypto_auth_hmacsha256_BYTES> key;
  crypto_auth_hmacsha256_final(&state, key.data());
  sodium_memzero(&state, sizeof(state));
  // 32 bytes is kMinSecretBytes: FromBytes cannot refuse it.
  FarmSecret derived = std::move(FarmSecret::FromBytes(key)).value();
  sodium_memzero(key.data(), key.size());
  return derived;
}

}  // namespace radfarm::protocol
