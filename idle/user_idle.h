// UserIdleSource: how long the machine's users have been inactive. The real source is logind
// (logind_user_idle.h); tests use a fake.
#pragma once

#include <chrono>
#include <string>

namespace radfarm::idle {

struct UserIdle {
  enum class State {
    kUnknown,  // no source could tell (no logind, no D-Bus): `detail` says why
    kActive,   // someone is using the machine
    kIdle,     // nobody has been active for `idle_for`
  };
  State state = State::kUnknown;
  std::chrono::seconds idle_for{0};
  std::string detail;
};

class UserIdleSource {
 public:
  virtual ~UserIdleSource() = default;
  // Called on the loop thread every few hundred milliseconds: must not block for long.
  virtual UserIdle Read() = 0;
};

}  // namespace radfarm::idle
