// `radfarm submit SCENE [--name --priority overrides...]`: validates the job locally exactly as
// `radfarm render` does (job file, overrides, OBJ/MTL, meshing), so a bad scene fails here with
// the same file:line message and exit 2 without contacting the master; then sends the job bundle
// (codec/job_bundle.h) and prints the new job's id alone on stdout.
#pragma once

#include <cstdint>
#include <string>

#include "cli/job_overrides.h"

namespace CLI {
class App;
}

namespace radfarm {

struct SubmitOptions {
  std::string scene;  // .obj or .toml
  std::string name;   // empty: the master names it job-ID
  int64_t priority = 0;
  JobOverrides overrides;
  bool json = false;
};

CLI::App* AddSubmitCommand(CLI::App& app, SubmitOptions* options);
int RunSubmit(const SubmitOptions& options, const std::string& control_path);

}  // namespace radfarm
