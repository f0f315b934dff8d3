#include "daemon/console/web/sign_in_guard.h"

#include <algorithm>

namespace radfarm::web {

SignInGuard::Duration SignInGuard::LockedFor(const std::string& address, TimePoint now) {
  std::lock_guard lock(mutex_);
  const auto it = records_.find(address);
  if (it == records_.end() || it->second.locked_until <= now) return Duration::zero();
  return it->second.locked_until - now;
}

uint32_t SignInGuard::Failed(const std::string& address, TimePoint now) {
  std::lock_guard lock(mutex_);
  Forget(now);
  if (!records_.count(address) && records_.size() >= kMaxAddresses) {
    records_.erase(std::min_element(records_.begin(), records_.end(), [](auto& a, auto& b) {
      return a.second.last < b.second.last;
    }));
  }
  Record& r = records_[address];
  ++r.failures;
  r.last = now;
  if (r.failures > kFreeFailures) {
    const uint32_t doublings = std::min<uint32_t>(r.failures - kFreeFailures - 1, 16);
    const Duration lockout = std::min<Duration>(kFirstLockout * (1u << doublings), kMaxLockout);
    r.locked_until = now + lockout;
  }
  return r.failures;
}

void SignInGuard::Succeeded(const std::string& address) {
  std::lock_guard lock(mutex_);
  records_.erase(address);
}

void SignInGuard::Forget(TimePoint now) {
  std::erase_if(records_, [now](const auto& entry) { return now - entry.second.last >= kForget; });
}

}  // namespace radfarm::web
