// Temporary directories and whole-file reads for tests and benchmarks.
#pragma once

#include <string>

namespace radfarm::testing {

// A fresh empty directory under the system temp dir (PREFIX-XXXXXX), removed with everything in it
// by the destructor. Throws std::runtime_error when it cannot be made.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "radfarm-test");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::string& path() const { return path_; }
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

// The bytes of `path`; empty when it cannot be read.
std::string ReadFile(const std::string& path);

}  // namespace radfarm::testing
