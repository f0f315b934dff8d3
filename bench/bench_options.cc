#include "bench/bench_options.h"

#include <string_view>

#include "bench/bench_json.h"
#include "scenegen/building_params.h"

namespace radfarm::bench {

bool ParseBenchOptions(int argc, char** argv, BenchOptions* options, std::string* error) {
  options->json_path = DefaultJsonPath("solver_bench");
  options->scenes_dir = RADFARM_SOURCE_DIR "/scenes";
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--quick") {
      options->quick = true;
    } else if (arg == "--raw-only") {
      options->raw_only = true;
    } else if (arg == "--raw-buildings" && i + 1 < argc) {
      std::string_view list = argv[++i];
      options->raw_buildings.clear();
      while (!list.empty()) {
        const size_t comma = list.find(',');
        const std::string rooms(list.substr(0, comma));
        if (Result<std::pair<int, int>> counts = scenegen::ParseRoomCounts(rooms); !counts) {
          *error = "--raw-buildings: " + counts.error();
          return false;
        }
        options->raw_buildings.push_back(rooms);
        list = comma == std::string_view::npos ? "" : list.substr(comma + 1);
      }
      if (options->raw_buildings.empty()) {
        *error = "--raw-buildings: the list is empty";
        return false;
      }
    } else if ((arg == "--json" || arg == "--scenes") && i + 1 < argc) {
      (arg == "--json" ? options->json_path : options->scenes_dir) = argv[++i];
    } else if (arg == "-h" || arg == "--help") {
      error->clear();
      return false;
    } else {
      *error = "unknown or incomplete argument '" + std::string(arg) + "'";
      return false;
    }
  }
  return true;
}

}  // namespace radfarm::bench
