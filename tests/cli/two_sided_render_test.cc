// Two-sided surfaces end to end, through the real binary: the rooms Blender's own exporters wrote
// (tests/blender/make_room.py), whose walls are two-sided. Their lit.glb has no coincident opposite
// triangles, which a viewer drawing back faces (Blender's Solid view) would z-fight on. Their lamp,
// a two-sided panel 2 cm under the ceiling, draws a warning (mesh/near_emitter_warnings.h) that a
// one-sided one does not.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"
#include "tests/output/coincident_triangles.h"

namespace radfarm {
namespace {

using testing::RunCommand;
using testing::TempDir;

tinygltf::Model LoadGlb(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path)) << err;
  return model;
}

class TwoSidedRoomTest : public ::testing::TestWithParam<const char*> {};

TEST_P(TwoSidedRoomTest, LitGlbHasNoCoincidentOppositeTriangles) {
  TempDir dir;
  const std::string out = dir.path() + "/out";
  const std::string job = std::string(RADFARM_SOURCE_DIR "/tests/blender/") + GetParam();
  const testing::CommandResult r =
      RunCommand({RADFARM_CLI_PATH, "render", job, "--out", out, "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_NE(r.err.find("warning: two-sided emitter 'lamp' lights a surface 0.02 away"),
            std::string::npos)
      << r.err;
  const std::vector<WorldTriangle> triangles = WorldTriangles(LoadGlb(out + "/lit.glb"));
  ASSERT_GT(triangles.size(), 100u);
  // The room is 4 m across: 0.1 mm is far below the layers' gap and far above float rounding.
  EXPECT_EQ(CoincidentOppositePairs(triangles, 1e-4), 0u);
}

INSTANTIATE_TEST_SUITE_P(BlenderRooms, TwoSidedRoomTest,
                         ::testing::Values("room-glb.toml", "room-obj.toml"));

TEST(TwoSidedRoomTest, AOneSidedLampUnderTheCeilingDrawsNoWarning) {
  TempDir dir;
  for (const char* file : {"room.obj", "room.mtl"}) {
    std::filesystem::copy_file(std::string(RADFARM_SOURCE_DIR "/tests/blender/") + file,
                               dir.path() + "/" + file);
  }
  const std::string job = dir.path() + "/room.toml";
  std::ofstream(job) << "scene = \"room.obj\"\ntwo_sided = true\n[materials.lamp]\n"
                        "two_sided = false\n[mesh]\npatch_size = 0.25\n[solver]\n"
                        "tolerance = 0.01\ngather_rays = 64\n[camera]\nwidth = 32\nheight = 24\n";
  const testing::CommandResult r =
      RunCommand({RADFARM_CLI_PATH, "render", job, "--out", dir.path() + "/out", "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.err.find("two-sided emitter"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace radfarm
