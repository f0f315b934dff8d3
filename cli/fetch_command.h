// `radfarm fetch ID --out DIR`: downloads a job's solution (its latest checkpoint) and writes
// image.png, image.exr, radiosity.ply, lit.glb, patches.csv and stats.json through the same code as
// `radfarm render` (render_outputs.h): the bundle the job was submitted with is meshed again, so
// the files match a local render of the same radiosity byte for byte (stats.json aside).
#pragma once

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace radfarm {

struct FetchOptions {
  uint64_t id = 0;
  std::string out_dir;
  bool json = false;
};

CLI::App* AddFetchCommand(CLI::App& app, FetchOptions* options);
int RunFetch(const FetchOptions& options, const std::string& control_path);

}  // namespace radfarm
