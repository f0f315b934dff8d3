// `radfarm render`: the embedded single-machine mode. Loads a scene or job file, meshes it, solves
// it on this machine's cores and writes image.png, image.exr, radiosity.ply, lit.glb, patches.csv
// and stats.json into the output directory.
#pragma once

#include <string>

#include "cli/job_overrides.h"

namespace CLI {
class App;
}

namespace radfarm {

struct RenderOptions {
  std::string scene;  // .obj or .toml
  std::string out_dir;
  JobOverrides overrides;
  bool quiet = false;  // no progress output
  std::string db;      // --db FILE: keep the rounds in a job store and resume from it
  std::string from;    // --from DIR: re-bake from the solution a render wrote in DIR
};

CLI::App* AddRenderCommand(CLI::App& app, RenderOptions* options);

// Runs the whole render; returns the process exit code (cli/exit_codes.h). Errors go to stderr as
// one line each, prefixed with "radfarm: ".
int RunRender(const RenderOptions& options);

}  // namespace radfarm
