#include "protocol/handshake_auth.h"

#include <sodium.h>

#include <cstring>

#include "base/result.h"

namespace radfarm::protocol {
namespace {

constexpr char kAgentLabel[] = "radfarm agent proof";  // sizeof includes the NUL
constexpr char kMasterLabel[] = "radfarm master proof";

class Mac {
 public:
  explicit Mac(const FarmSecret& secret) {
    crypto_auth_hmacsha256_init(&state_, secret.bytes().data(), secret.bytes().size());
  }
  ~Mac() { sodium_memzero(&state_, sizeof(state_)); }

  void Add(const void* data, size_t size) {
    crypto_auth_hmacsha256_update(&state_, static_cast<const unsigned char*>(data), size);
  }
  void AddU16(uint16_t v) {
    const uint8_t b[2] = {static_cast<uint8_t>(v), static_cast<uint8_t>(v >> 8)};
    Add(b, sizeof(b));
  }
  void AddU32(uint32_t v) {
    const uint8_t b[4] = {static_cast<uint8_t>(v), static_cast<uint8_t>(v >> 8),
                          static_cast<uint8_t>(v >> 16), static_cast<uint8_t>(v >> 24)};
    Add(b, sizeof(b));
  }
  Tag Finish() {
    Tag tag;
    crypto_auth_hmacsha256_final(&state_, tag.data());
    return tag;
  }

 private:
  crypto_auth_hmacsha256_state state_;
};

}  // namespace

Tag TranscriptMac(const FarmSecret& secret, const char* label, size_t label_size,
                  const HelloMsg& hello, const ChallengeMsg& challenge) {
  Mac mac(secret);
  mac.Add(label, label_size);
  mac.AddU16(hello.min_version);
  mac.AddU16(hello.max_version);
  mac.AddU32(static_cast<uint32_t>(hello.agent_name.size()));
  mac.Add(hello.agent_name.data(), hello.agent_name.size());
  mac.AddU32(hello.threads);
  mac.Add(hello.nonce.data(), hello.nonce.size());
  mac.AddU16(challenge.version);
  mac.Add(challenge.nonce.data(), challenge.nonce.size());
  return mac.Finish();
}

Status InitSodium() {
  // sodium_init is itself safe to call from several threads; the static keeps it to one call.
  static const int result = sodium_init();
  if (result < 0) return Error{"libsodium failed to initialise"};
  return Ok{};
}

Result<Nonce> FreshNonce() {
  RADFARM_RETURN_IF_ERROR(InitSodium());
  Nonce nonce;
  randombytes_buf(nonce.data(), nonce.size());
  return nonce;
}

Tag AgentTag(const FarmSecret& secret, const HelloMsg& hello, const ChallengeMsg& challenge) {
  return TranscriptMac(secret, kAgentLabel, sizeof(kAgentLabel), hello, challenge);
}

Tag MasterTag(const FarmSecret& secret, const HelloMsg& hello, const ChallengeMsg& challenge) {
  return TranscriptMac(secret, kMasterLabel, sizeof(kMasterLabel), hello, challenge);
}

bool TagsEqual(const Tag& a, const Tag& b) {
  return sodium_memcmp(a.data(), b.data(), a.size()) == 0;
}

}  // namespace radfarm::protocol
