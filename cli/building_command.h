// `radfarm building --out DIR [...]`: writes a procedural office building (scenegen/) as
// DIR/NAME.obj, NAME.mtl and NAME.toml, a job that `radfarm render` and `radfarm submit` take as
// any user scene. Sizes from a few thousand patches (1 room) to millions (--floors, --rooms).
#pragma once

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace radfarm {

struct BuildingOptions {
  std::string out;
  std::string name = "building";
  int floors = 1;
  std::string rooms = "2x2";
  std::string room_size = "4x4";
  std::string lights = "2x1";  // ceiling panels per room
  double height = 3;
  uint64_t seed = 1;
  bool windows = false;
  bool no_furniture = false;
  double patch_size = 0.25;  // written to the job file; 0: automatic
  // Written to the job file; 0: no refinement. Refinement lowers the building's display error
  // against uniform patches, for about twice the render time (docs/BENCHMARKS-accuracy.md).
  double refine_tolerance = 0.05;
};

CLI::App* AddBuildingCommand(CLI::App& app, BuildingOptions* options);
int RunBuilding(const BuildingOptions& options);

}  // namespace radfarm
