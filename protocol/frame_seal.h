// The frames after the handshake, sealed: each direction has its own key, derived from the farm
// secret and the handshake transcript (both fresh nonces), and every frame is sealed with
// ChaCha20-Poly1305-IETF (libsodium), its nonce an implicit per-direction frame counter and its
// length prefix the associated data.
//
//   key agent->master = HMAC(secret, "radfarm agent to master key\0" || transcript)
//   key master->agent = HMAC(secret, "radfarm master to agent key\0" || transcript)
//   sealed frame      = length (u32 LE, = n + 16) || AEAD(key, nonce = 0^4 || counter (u64 LE),
//                       ad = the 4 length bytes, the n bytes of the FlatBuffer) || 16-byte tag
//
// The counter starts at 0 with the first frame after Welcome and is never sent: a dropped,
// reordered or replayed frame is opened under the wrong nonce and fails, as does a modified or
// injected one (no key) and one reflected back (the other direction's key). Fresh nonces give
// every connection fresh keys, so a recorded session fails against any new connection.
//
// SealMode::kAuthenticateOnly leaves the FlatBuffer in clear and authenticates prefix and body
// (the AEAD over empty plaintext): integrity without confidentiality. It exists to measure what
// encryption costs (farm_bench); both ends must use the same mode, which the environment variable
// RADFARM_WIRE_SEAL=authenticate-only selects. Nothing in the handshake negotiates it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "protocol/farm_secret.h"
#include "protocol/limits.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

inline constexpr size_t kSealKeyBytes = 32;
inline constexpr size_t kSealTagBytes = 16;  // Poly1305

enum class SealMode { kEncrypt, kAuthenticateOnly };

// kEncrypt unless RADFARM_WIRE_SEAL=authenticate-only (read once per process).
SealMode SealModeFromEnvironment();

struct SessionKeys {
  ~SessionKeys();  // wipes the keys
  std::array<uint8_t, kSealKeyBytes> agent_to_master{};
  std::array<uint8_t, kSealKeyBytes> master_to_agent{};
};

SessionKeys DeriveSessionKeys(const FarmSecret& secret, const HelloMsg& hello,
                              const ChallengeMsg& challenge);

// One direction of a connection: seals (sender) or opens (receiver) its frames in order. The key
// is wiped when destroyed.
class FrameSeal {
 public:
  FrameSeal(const std::array<uint8_t, kSealKeyBytes>& key, SealMode mode);
  ~FrameSeal();
  FrameSeal(FrameSeal&& other) noexcept;
  FrameSeal& operator=(FrameSeal&& other) noexcept;
  FrameSeal(const FrameSeal&) = delete;
  FrameSeal& operator=(const FrameSeal&) = delete;

  // `frame` is a whole plaintext frame (EncodeFrame: prefix + body); returns the sealed frame.
  std::vector<uint8_t> Seal(std::span<const uint8_t> frame);
  // `body` is what follows a sealed frame's length prefix; returns the FlatBuffer. Fails
  // ("frame failed authentication") if the frame is not the next one sealed with this key.
  Result<std::vector<uint8_t>> Open(std::span<const uint8_t> body);

  // Frames sealed or opened so far.
  uint64_t counter() const { return counter_; }

 private:
  std::array<uint8_t, kSealKeyBytes> key_{};
  SealMode mode_;
  uint64_t counter_ = 0;
};

}  // namespace radfarm::protocol
