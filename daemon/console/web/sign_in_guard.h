// SignInGuard: slows down guessing the web token, per client address. The first kFreeFailures
// wrong tokens from an address cost nothing; each one after locks the address out for twice as
// long as the last (kFirstLockout, up to kMaxLockout). A locked-out address is answered at once
// with 429, so no HTTP thread sleeps and nobody else waits. An address's failures are forgotten
// kForget after its last one, or when it signs in; at most kMaxAddresses are remembered (a new
// one then forgets the longest quiet).
//
// Pure logic with the clock passed in. Thread-safe: the HTTP threads share one.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace radfarm::web {

class SignInGuard {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;
  using Duration = std::chrono::steady_clock::duration;
  static constexpr uint32_t kFreeFailures = 5;
  static constexpr std::chrono::seconds kFirstLockout{1};
  static constexpr std::chrono::seconds kMaxLockout{300};
  static constexpr std::chrono::minutes kForget{15};
  static constexpr size_t kMaxAddresses = 4096;

  // How long `address` must still wait before a token from it is looked at (zero: not at all).
  Duration LockedFor(const std::string& address, TimePoint now);
  // A wrong token from `address`; returns its failures so far.
  uint32_t Failed(const std::string& address, TimePoint now);
  // A right one: its failures are forgotten.
  void Succeeded(const std::string& address);

 private:
  struct Record {
    uint32_t failures = 0;
    TimePoint last;
    TimePoint locked_until;
  };
  void Forget(TimePoint now);

  std::mutex mutex_;
  std::map<std::string, Record> records_;
};

}  // namespace radfarm::web
