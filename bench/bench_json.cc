#include "bench/bench_json.h"

#include <filesystem>
#include <stdexcept>

#include "base/atomic_file.h"

namespace radfarm::bench {

std::string DefaultJsonPath(const std::string& program) {
  return std::string(RADFARM_SOURCE_DIR) + "/bench/results/" + program + ".json";
}

nlohmann::json MachineJson(const MachineInfo& m) {
  return {{"date", m.date},
          {"cpus", m.cpus},
          {"cpu_model", m.cpu_model},
          {"load_average", m.load_average},
          {"compiler", m.compiler},
          {"embree_version", m.embree_version},
          {"command_line", m.command_line}};
}

void WriteJson(const std::string& path, const nlohmann::json& json) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const Status written = WriteFileAtomically(path, json.dump(1) + "\n");
  if (!written.ok()) throw std::runtime_error(written.error());
}

}  // namespace radfarm::bench
