#include "bench/bench_scene.h"

#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "bench/stopwatch.h"
#include "input/input_scene.h"
#include "scenegen/building.h"
#include "scenegen/obj_writer.h"
#include "scenegen/room_layout.h"

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

std::string WriteBuildingJob(const scenegen::BuildingParams& params, double patch_size,
                             const std::string& dir, const std::string& name) {
  Result<scenegen::SceneModel> model = scenegen::GenerateBuilding(params);
  if (!model.ok()) throw std::runtime_error(model.error());
  const scenegen::RoomView view = scenegen::FirstRoomView(params);
  scenegen::JobFileSettings job;
  job.patch_size = patch_size;
  job.eye = view.eye;
  job.target = view.target;
  Result<std::string> written = scenegen::WriteScene(*model, dir, name, job);
  if (!written.ok()) throw std::runtime_error(written.error());
  return *written;
}

BenchScene LoadBuildingBenchScene(const std::string& name, const scenegen::BuildingParams& params,
                                  double patch_size) {
  Result<scenegen::SceneModel> model = scenegen::GenerateBuilding(params);
  if (!model.ok()) throw std::runtime_error(model.error());
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("radfarm-bench-" + name + "-" + std::to_string(::getpid()));
  const Result<std::string> written = scenegen::WriteScene(*model, dir.string(), name, {});
  if (!written.ok()) throw std::runtime_error(written.error());
  struct RemoveDir {
    std::filesystem::path dir;
    ~RemoveDir() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } remove{dir};
  BenchScene scene = LoadBenchScene(name, (dir / (name + ".obj")).string(), patch_size);
  scene.path = "radfarm building --floors " + std::to_string(params.floors) + " --rooms " +
               std::to_string(params.rooms_x) + "x" + std::to_string(params.rooms_z);
  if (params.room_width != 4 || params.room_depth != 4) {
    std::ostringstream size;
    size << " --room-size " << params.room_width << "x" << params.room_depth;
    scene.path += size.str();
  }
  if (params.lights_x != 2 || params.lights_z != 1) {
    scene.path +=
        " --lights " + std::to_string(params.lights_x) + "x" + std::to_string(params.lights_z);
  }
  return scene;
}

}  // namespace radfarm::bench
