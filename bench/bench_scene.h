// A benchmark scene: an OBJ meshed into patches once, then solved many times.
#pragma once

#include <memory>
#include <string>

#include "core/patch_scene.h"
#include "mesh/patch_mesh.h"
#include "scenegen/building_params.h"

namespace radfarm::bench {

struct BenchScene {
  std::string name;       // short name for tables and file names, e.g. "cornell-box"
  std::string path;       // the OBJ as given
  double patch_size = 0;  // as given to LoadBenchScene
  std::unique_ptr<PatchMesh> mesh;
  double load_seconds = 0;  // LoadObjScene + PatchMesh::Build

  const PatchScene& patches() const { return mesh->patch_scene(); }
};

// Loads and meshes `path` with the given patch size (0: automatic). Throws std::runtime_error with
// the loader's or mesher's message on failure.
BenchScene LoadBenchScene(const std::string& name, const std::string& path, double patch_size);

// The procedural building as `radfarm building` writes it (its job file with `patch_size`, 0 for
// automatic, and the camera in the first room), as DIR/NAME.obj, .mtl and .toml: the job file's
// path. Throws std::runtime_error with the generator's or writer's message on failure.
std::string WriteBuildingJob(const scenegen::BuildingParams& params, double patch_size,
                             const std::string& dir, const std::string& name);

// The procedural building (scenegen/) as `radfarm building` writes it: generated, written to a
// temporary directory, loaded and meshed like any OBJ; the files are removed afterwards.
BenchScene LoadBuildingBenchScene(const std::string& name, const scenegen::BuildingParams& params,
                                  double patch_size);

}  // namespace radfarm::bench
