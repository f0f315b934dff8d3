// A SQLite VFS for fault injection, in the manner of SQLite's own test6.c: "radfarm_faulty" wraps
// the default VFS and, once armed, fails writes with SQLITE_IOERR_WRITE. Open a store with
// DatabaseOptions::vfs = kFaultyVfsName. Registered on first use; process-wide, so tests that arm
// it must disarm it (FaultyVfsArm does so in its destructor).
#pragma once

namespace radfarm::store {

inline constexpr const char* kFaultyVfsName = "radfarm_faulty";

void RegisterFaultyVfs();

// While alive: the first `writes_before_failure` writes succeed, every later one fails.
class FaultyVfsArm {
 public:
  explicit FaultyVfsArm(int writes_before_failure);
  ~FaultyVfsArm();
  FaultyVfsArm(const FaultyVfsArm&) = delete;
  FaultyVfsArm& operator=(const FaultyVfsArm&) = delete;
  int failures() const;  // writes refused so far
};

}  // namespace radfarm::store
