#include "bench/bench_options.h"

#include <string_view>

#include "bench/bench_json.h"

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
