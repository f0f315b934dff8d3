// Per-agent credentials: an enrolled agent proves itself with its own key instead of the farm
// secret, so one agent can be cut off without re-keying the farm.
//
//   agent key = HMAC-SHA-256(farm secret, "radfarm agent key\0" || name length (u32 LE) || name
//                            || generation (u64 LE))
//
// The master derives it again from the name and the generation it stored when it enrolled the
// agent, so it keeps no key on disk; enrolling the name again (after a revoke) bumps the
// generation and gives a new key, and the old one no longer matches. Only the master can make a
// key (it needs the farm secret); an agent key reveals nothing about the farm secret.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.h"
#include "protocol/farm_secret.h"

namespace radfarm::protocol {

FarmSecret DeriveAgentKey(const FarmSecret& farm_secret, std::string_view name,
                          uint64_t generation);

// The key the master expects from the agent named in a Hello, and how to name it in logs
// ("the farm secret", "the enrolled key of NAME (generation G)").
struct ExpectedKey {
  FarmSecret key;
  std::string description;
};

}  // namespace radfarm::protocol
