#include "cli/rebake_inputs.h"

#include <filesystem>

#include "codec/patch_scene_codec.h"
#include "protocol/scene_transfer.h"

namespace radfarm {
namespace {

std::string HashOf(const PatchScene& scene) {
  return protocol::HashToHex(protocol::HashScene(codec::EncodePatchScene(scene)));
}

}  // namespace

SceneHashes HashesOf(const PatchScene& scene) {
  // Reflectance and emission never change the mesh; the lamps and the sky are recorded apart,
  // since a change of theirs makes the re-bake trace its start again (a change of emission only
  // the change's).
  PatchScene lamps = scene;
  for (Patch& p : lamps.patches) p.reflectance = p.emission = Rgb{};
  PatchScene bare = lamps;
  bare.lights.clear();
  bare.sky = Sky{};
  return {HashOf(bare), HashOf(lamps)};
}

Result<PreviousSolve> LoadPreviousSolve(const std::string& dir, const PatchScene& scene,
                                        const SceneHashes& hashes) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    return Error{"--from " + dir + ": not a directory (the output directory of a render)"};
  }
  const std::string path = (std::filesystem::path(dir) / kPreviousSolveFile).string();
  if (!std::filesystem::exists(path, ec)) {
    return Error{"--from " + dir + ": no " + kPreviousSolveFile +
                 " in it: not the output directory of a render"};
  }
  Result<PreviousSolve> previous = ReadPreviousSolve(path);
  if (!previous) return Error{"--from " + previous.error()};
  if (previous->geometry_hash != hashes.geometry) {
    return Error{"--from " + dir + ": its solution has " +
                 std::to_string(previous->values.radiosity.size()) +
                 " patches of another mesh (this scene meshes to " +
                 std::to_string(scene.patches.size()) +
                 "): a re-bake needs the same geometry and mesh settings; render it in full"};
  }
  return previous;
}

StartLightSource ReusedStart(const PreviousSolve& previous, const SolverSettings& settings,
                             const SceneHashes& hashes) {
  if (previous.lamps_hash != hashes.lamps) return {};
  return RebakeStart(previous.values, settings.threads);
}

PreviousSolve PreviousSolveOf(const PatchScene& scene, const SolverSettings& settings,
                              const SolveResult& solution) {
  const SceneHashes hashes = HashesOf(scene);
  PreviousSolve out{hashes.geometry, hashes.lamps, std::nullopt, {}};
  if (!solution.direct_light.empty()) out.start_work = StartWorkOf(scene, settings);
  out.values = PreviousValuesOf(scene, solution);
  return out;
}

}  // namespace radfarm
