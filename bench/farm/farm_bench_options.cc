#include "bench/farm/farm_bench_options.h"

#include <string_view>

#include "bench/bench_json.h"

namespace radfarm::bench {

bool ParseFarmBenchOptions(int argc, char** argv, FarmBenchOptions* options, std::string* error) {
  options->json_path = DefaultJsonPath("farm_bench");
  options->scenes_dir = RADFARM_SOURCE_DIR "/scenes";
  options->radfarmd = RADFARMD_PATH;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--quick") {
      options->quick = true;
    } else if ((arg == "--json" || arg == "--scenes") && i + 1 < argc) {
      (arg == "--json" ? options->json_path : options->scenes_dir) = argv[++i];
    } else if (arg == "--radfarmd" && i + 1 < argc) {
      options->radfarmd = argv[++i];
    } else if (arg == "--only" && i + 1 < argc) {
      const std::string_view part = argv[++i];
      if (part != "real" && part != "sim" && part != "capacity") {
        *error = "--only takes 'real', 'sim' or 'capacity', not '" + std::string(part) + "'";
        return false;
      }
      options->real = part == "real";
      options->simulated = part != "real";
      options->capacity_only = part == "capacity";
    } else if ((arg == "--agents" || arg == "--repetitions") && i + 1 < argc) {
      const std::string text = argv[++i];
      if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
          text.size() > 6 || std::stoul(text) == 0) {
        *error = std::string(arg) + " takes a positive number, not '" + text + "'";
        return false;
      }
      if (arg == "--agents") {
        options->agents = std::stoul(text);
      } else {
        options->repetitions = std::stoi(text);
      }
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
