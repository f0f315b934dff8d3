// Every shipped scene rendered with its defaults, its outputs' SHA-256s checked against committed
// values (golden_render.sha256): a refactor that changes one bit of patches.csv, image.exr,
// radiosity.ply or lit.glb fails here. A change that means to alter the results regenerates the
// file in the same commit: RADFARM_UPDATE_GOLDEN=1 build/tests/cli/cli_test
// --gtest_filter='GoldenRender*'.
#include <gtest/gtest.h>
#include <sodium.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"
#include "tests/cli/shipped_scenes.h"

namespace radfarm {
namespace {

using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

const std::string kGoldenScenes = RADFARM_SOURCE_DIR "/scenes/";
const std::string kGoldenFile = RADFARM_SOURCE_DIR "/tests/cli/golden_render.sha256";
const char* const kCheckedFiles[] = {"patches.csv", "image.exr", "radiosity.ply", "lit.glb"};

// Every job file, and every OBJ (a bare OBJ is a job of its own: automatic camera, defaults) but
// those lit only by a job's IES lamps.
std::vector<std::string> ShippedScenes() {
  std::vector<std::string> scenes;
  const std::set<std::filesystem::path> lamp_lit = testing::ScenesLitByJobLamps(kGoldenScenes);
  for (const auto& entry : std::filesystem::directory_iterator(kGoldenScenes)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".obj" && lamp_lit.contains(std::filesystem::weakly_canonical(entry.path()))) {
      continue;
    }
    if (ext == ".toml" || ext == ".obj") scenes.push_back(entry.path().filename().string());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// Scenes whose defaults take minutes are rendered with a ray budget (still one deterministic job).
std::vector<std::string> ExtraArguments(const std::string& scene) {
  if (scene == "high-albedo.obj") return {"--rays", "3000000"};  // reflectance 0.999
  return {};
}

std::string Sha256Hex(const std::string& bytes) {
  unsigned char digest[crypto_hash_sha256_BYTES];
  crypto_hash_sha256(digest, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned char c : digest) {
    hex += kHex[c >> 4];
    hex += kHex[c & 15];
  }
  return hex;
}

// "scene/file" -> hash, from lines "HASH  scene/file" (sha256sum's format).
std::map<std::string, std::string> ReadGolden() {
  std::map<std::string, std::string> golden;
  std::istringstream in(ReadFile(kGoldenFile));
  std::string hash, name;
  while (in >> hash >> name) golden[name] = hash;
  return golden;
}

TEST(GoldenRenderTest, EveryShippedSceneRendersToItsCommittedBytes) {
  ASSERT_EQ(sodium_init() >= 0, true);
  const bool update = std::getenv("RADFARM_UPDATE_GOLDEN") != nullptr;
  const std::map<std::string, std::string> golden = ReadGolden();
  std::ostringstream fresh;
  for (const std::string& scene : ShippedScenes()) {
    SCOPED_TRACE(scene);
    TempDir dir;
    std::vector<std::string> args = {RADFARM_CLI_PATH, "render",   kGoldenScenes + scene,
                                     "--out",          dir.path(), "--quiet"};
    for (const std::string& extra : ExtraArguments(scene)) args.push_back(extra);
    const auto r = RunCommand(args);
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    for (const char* file : kCheckedFiles) {
      const std::string name = scene + "/" + file;
      const std::string hash = Sha256Hex(ReadFile(dir.File(file)));
      fresh << hash << "  " << name << "\n";
      if (update) continue;
      const auto it = golden.find(name);
      ASSERT_NE(it, golden.end()) << name << " has no committed hash; its hash is " << hash;
      EXPECT_EQ(hash, it->second) << name << " changed";
    }
  }
  if (update) {
    std::ofstream(kGoldenFile) << fresh.str();
  } else {
    EXPECT_EQ(golden.size(), ShippedScenes().size() * std::size(kCheckedFiles))
        << "golden_render.sha256 names a scene that is no longer shipped";
  }
}

}  // namespace
}  // namespace radfarm
