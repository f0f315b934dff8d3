#include "daemon/console/web/session_table.h"

#include <sodium.h>

#include <algorithm>
#include <array>
#include <cstdlib>

namespace radfarm::web {
namespace {

std::string Hex(const unsigned char* bytes, size_t n) {
  std::string hex(2 * n + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), bytes, n);
  hex.pop_back();
  return hex;
}

std::string KeyOf(std::string_view session) {
  std::array<unsigned char, crypto_generichash_BYTES> hash{};
  crypto_generichash(hash.data(), hash.size(),
                     reinterpret_cast<const unsigned char*>(session.data()), session.size(),
                     nullptr, 0);
  return Hex(hash.data(), hash.size());
}

}  // namespace

std::string SessionTable::Begin(TimePoint now) {
  if (sodium_init() < 0) std::abort();  // libsodium cannot work at all; nothing to fall back on
  std::array<unsigned char, 32> bytes{};
  randombytes_buf(bytes.data(), bytes.size());
  std::string session = Hex(bytes.data(), bytes.size());
  std::lock_guard lock(mutex_);
  DropExpired(now);
  if (sessions_.size() >= kMaxSessions) {
    sessions_.erase(std::min_element(sessions_.begin(), sessions_.end(), [](auto& a, auto& b) {
      return a.second.used < b.second.used;
    }));
  }
  sessions_[KeyOf(session)] = Entry{now, now};
  return session;
}

bool SessionTable::Use(std::string_view session, TimePoint now) {
  if (session.empty()) return false;
  const std::string key = KeyOf(session);
  std::lock_guard lock(mutex_);
  DropExpired(now);
  const auto it = sessions_.find(key);
  if (it == sessions_.end()) return false;
  it->second.used = now;
  return true;
}

bool SessionTable::End(std::string_view session, TimePoint now) {
  const std::string key = KeyOf(session);
  std::lock_guard lock(mutex_);
  DropExpired(now);
  return sessions_.erase(key) > 0;
}

size_t SessionTable::live(TimePoint now) {
  std::lock_guard lock(mutex_);
  DropExpired(now);
  return sessions_.size();
}

void SessionTable::DropExpired(TimePoint now) {
  std::erase_if(sessions_, [now](const auto& entry) {
    return now - entry.second.used >= kIdle || now - entry.second.began >= kMaxAge;
  });
}

}  // namespace radfarm::web
