// Helpers for the packaging tests, which drive command-line tools (cpack, dpkg-deb,
// systemd-analyze): run a command, find a tool, own a temporary directory.
#pragma once

#include <filesystem>
#include <string>

namespace radfarm::packaging::testing {

struct CommandResult {
  int exit_code = -1;  // -1: it did not run or was killed
  std::string output;  // stdout and stderr together
};

// Runs `command` through /bin/sh and waits for it.
CommandResult RunCommand(const std::string& command);

// Whether `tool` is on PATH.
bool HaveTool(const std::string& tool);

// Quotes `text` for /bin/sh.
std::string Quote(const std::string& text);

std::string ReadFile(const std::filesystem::path& path);

// A fresh directory under /tmp, removed with everything in it on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace radfarm::packaging::testing
