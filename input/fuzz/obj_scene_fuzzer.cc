// libFuzzer target: an OBJ and its MTL library (the input cut at kFuzzPartSeparator: OBJ first,
// then the MTL, written as scene.obj and scene.mtl; without a separator there is no MTL file)
// through LoadScene. Any input must give a scene or an error: no crash, leak, UB or hang, and an
// accepted scene must pass CheckLoadedScene.
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/fuzz/fuzz_files.h"
#include "input/fuzz/loaded_scene_check.h"
#include "input/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::fuzz;
  const auto parts = SplitFuzzInput(std::span(data, size), 2);
  const std::filesystem::path dir = FuzzScratchDirectory();
  WriteFuzzFile(dir / "scene.obj", parts[0]);
  if (parts.size() > 1) {
    WriteFuzzFile(dir / "scene.mtl", parts[1]);
  } else {
    std::filesystem::remove(dir / "scene.mtl");
  }
  // A small limit, so files over it are refused too (they are, from their size alone).
  auto scene = radfarm::LoadScene((dir / "scene.obj").string(), 1u << 20);
  if (scene) CheckLoadedScene(*scene);
  return 0;
}
