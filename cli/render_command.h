// `radfarm render`: the embedded single-machine mode. Loads a scene or job file, meshes it, solves
// it on this machine's cores and writes image.png, image.exr, radiosity.ply, patches.csv and
// stats.json into the output directory.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace radfarm {

struct RenderOptions {
  std::string scene;  // .obj or .toml
  std::string out_dir;
  // Command-line overrides of the job's settings; unset means "as the job file says".
  std::optional<uint32_t> threads;
  std::optional<uint64_t> seed;
  std::optional<double> tolerance;
  std::optional<uint64_t> rays;
  std::optional<double> seconds;
  std::optional<std::string> sampler;
  std::optional<double> patch_size;
  bool quiet = false;  // no progress output
};

// Runs the whole render; returns the process exit code (cli/exit_codes.h). Errors go to stderr as
// one line each, prefixed with "radfarm: ".
int RunRender(const RenderOptions& options);

}  // namespace radfarm
