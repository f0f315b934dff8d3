// Runs the real radfarm binary as a child process and captures its exit code, stdout and stderr.
#pragma once

#include <string>
#include <vector>

namespace radfarm::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `args` (args[0] is the program path) with no shell involved; waits for it to finish.
CommandResult RunCommand(const std::vector<std::string>& args);
// The same with the environment changed: "NAME=value" sets a variable, "NAME" removes it.
CommandResult RunCommand(const std::vector<std::string>& args,
                         const std::vector<std::string>& env_changes);

// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

std::string ReadFile(const std::string& path);

}  // namespace radfarm::testing
