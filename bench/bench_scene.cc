#include "bench/bench_scene.h"

#include <stdexcept>
#include <vector>

#include "bench/stopwatch.h"
#include "input/input_scene.h"

namespace radfarm::bench {

BenchScene LoadBenchScene(const std::string& name, const std::string& path, double patch_size) {
  const Stopwatch clock;
  Result<InputScene> input = LoadObjScene(path);
  if (!input.ok()) throw std::runtime_error(input.error());
  MeshSettings settings;
  settings.patch_size = patch_size;
  std::vector<std::string> warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(*input, settings, &warnings);
  if (!mesh.ok()) throw std::runtime_error(mesh.error());
  BenchScene scene;
  scene.name = name;
  scene.path = path;
  scene.patch_size = patch_size;
  scene.mesh = std::make_unique<PatchMesh>(std::move(mesh).value());
  scene.load_seconds = clock.Seconds();
  return scene;
}

}  // namespace radfarm::bench
