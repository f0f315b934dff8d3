// SessionTable: the page's sign-ins. Each sign-in (the web token traded on POST /api/session)
// gets its own random session token, which the page keeps in sessionStorage (bound to the
// console's origin, port included) and sends as "Authorization: Bearer SESSION". Nothing rides in
// a cookie, so a page on another port of the same host, which the browser would hand a cookie
// to, has nothing to replay.
//
// A session ends when it has not been used for kIdle, kMaxAge after it began, on sign-out (End),
// or when the master stops (the table lives in memory only). At most kMaxSessions live at once:
// a new one then ends the longest unused.
//
// Pure logic with the clock passed in. Thread-safe: the HTTP threads share one.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <string_view>

namespace radfarm::web {

class SessionTable {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;
  static constexpr std::chrono::minutes kIdle{30};
  static constexpr std::chrono::hours kMaxAge{12};
  static constexpr size_t kMaxSessions = 256;

  // A new session: 32 random bytes as 64 hex digits.
  std::string Begin(TimePoint now);
  // Whether `session` is live at `now`; a live one's idle time starts again.
  bool Use(std::string_view session, TimePoint now);
  // Ends `session`; false when it was not live.
  bool End(std::string_view session, TimePoint now);
  size_t live(TimePoint now);

 private:
  struct Entry {
    TimePoint began;
    TimePoint used;
  };
  void DropExpired(TimePoint now);

  std::mutex mutex_;
  // Keyed by a hash of the session, so that finding one reveals nothing of others by its timing.
  std::map<std::string, Entry> sessions_;
};

}  // namespace radfarm::web
