// FileUserIdle: the user's activity read from a file instead of logind (--idle-source FILE), so
// tests can play a user who comes and goes, and operators can drive the idle policy from their own
// tool. The file holds one word:
//
//   idle   nobody is using the machine, since the file was last written (its mtime): the policy's
//          user_idle_minutes counts from then
//   busy   someone is (also "active")
//
// A missing or unreadable file, or any other content, reads as "unknown", which the idle policy
// treats as idle and logs once (idle/idle_policy.h). Writers should replace the file atomically
// (write a temporary file, then rename it over this one). The file is read on the loop thread
// every half second: it must be a small local file.
#pragma once

#include <string>

#include "idle/user_idle.h"

namespace radfarm::agent {

class FileUserIdle : public idle::UserIdleSource {
 public:
  explicit FileUserIdle(std::string path) : path_(std::move(path)) {}
  idle::UserIdle Read() override;

 private:
  std::string path_;
};

}  // namespace radfarm::agent
