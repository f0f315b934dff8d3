// The cryptography of the handshake (libsodium): fresh nonces, and HMAC-SHA-256 tags over the
// handshake transcript, one per direction.
//
//   agent tag  = HMAC(secret, "radfarm agent proof\0"  || transcript)
//   master tag = HMAC(secret, "radfarm master proof\0" || transcript)
//   transcript = Hello (min and max version, name, threads, agent nonce)
//                || Challenge (chosen version, master nonce), integers little-endian,
//                the name preceded by its length
//
// Both nonces make every tag unique to one connection (no replay); the different labels stop a
// tag from one direction being reflected back as the other; covering the whole Hello and
// Challenge stops a man in the middle from changing the name or forcing an older version.
#pragma once

#include "base/result.h"
#include "protocol/farm_secret.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

// Starts libsodium once per process (thread-safe). Fails only if it cannot get entropy.
Status InitSodium();

// 32 bytes from libsodium's CSPRNG.
Result<Nonce> FreshNonce();

// HMAC(secret, label || transcript), the label with its terminating NUL (sizeof a literal). The
// proofs below and the session keys (frame_seal.h) are this with different labels.
Tag TranscriptMac(const FarmSecret& secret, const char* label, size_t label_size,
                  const HelloMsg& hello, const ChallengeMsg& challenge);

Tag AgentTag(const FarmSecret& secret, const HelloMsg& hello, const ChallengeMsg& challenge);
Tag MasterTag(const FarmSecret& secret, const HelloMsg& hello, const ChallengeMsg& challenge);

// Constant-time comparison (sodium_memcmp): timing does not reveal how many bytes matched.
bool TagsEqual(const Tag& a, const Tag& b);

}  // namespace radfarm::protocol
