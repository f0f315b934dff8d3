// `radfarm agents enroll NAME`, `radfarm agents revoke NAME` and `radfarm agents enrolled`: per-agent
// credentials
// (docs/OPERATIONS.md, "Agent keys"). The master derives an enrolled agent's key from the farm
// secret, the name and a generation it stores; `enroll` writes that key where the agent's
// secret_file can read it, `revoke` cuts the agent off at once.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace radfarm {

struct EnrollOptions {
  std::string name;
  std::string out = "-";  // the key file to write; "-": stdout
  bool force = false;
  bool json = false;
};

struct RevokeOptions {
  std::string name;
  bool json = false;
};

struct EnrolledOptions {
  bool json = false;
};

// All are subcommands of `agents`.
CLI::App* AddEnrollCommand(CLI::App& agents, EnrollOptions* options);
CLI::App* AddRevokeCommand(CLI::App& agents, RevokeOptions* options);
CLI::App* AddEnrolledCommand(CLI::App& agents, EnrolledOptions* options);
int RunEnroll(const EnrollOptions& options, const std::string& control_path);
int RunRevoke(const RevokeOptions& options, const std::string& control_path);
int RunEnrolled(const EnrolledOptions& options, const std::string& control_path);

}  // namespace radfarm
