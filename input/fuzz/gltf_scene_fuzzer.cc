// libFuzzer target: a glTF scene through LoadScene. The input is cut at kFuzzPartSeparator into
// the scene file (scene.glb when it starts with the binary magic "glTF", else scene.gltf), then
// buffer.bin and image.png, which a .gltf may reference by those names. Any input must give a
// scene or an error: no crash, leak, UB or hang, and an accepted scene must pass
// CheckLoadedScene.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/fuzz/fuzz_files.h"
#include "input/fuzz/loaded_scene_check.h"
#include "input/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::fuzz;
  const auto parts = SplitFuzzInput(std::span(data, size), 3);
  const std::filesystem::path dir = FuzzScratchDirectory();
  const bool binary = parts[0].substr(0, 4) == "glTF";
  const std::filesystem::path scene = dir / (binary ? "scene.glb" : "scene.gltf");
  std::filesystem::remove(dir / (binary ? "scene.gltf" : "scene.glb"));
  WriteFuzzFile(scene, parts[0]);
  const char* extra_names[] = {"buffer.bin", "image.png"};
  for (size_t i = 0; i < 2; ++i) {
    if (i + 1 < parts.size()) {
      WriteFuzzFile(dir / extra_names[i], parts[i + 1]);
    } else {
      std::filesystem::remove(dir / extra_names[i]);
    }
  }
  // A small limit, so oversized scene files, buffers and images are refused too.
  auto loaded = radfarm::LoadScene(scene.string(), 1u << 20);
  if (loaded) CheckLoadedScene(*loaded);
  return 0;
}
