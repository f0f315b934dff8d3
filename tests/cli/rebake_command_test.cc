// `radfarm render --from DIR`: a re-bake from a previous render's rebake.bin, end to end with the
// real binary: the same bits on any threads, cheaper than the full render it replaces, and the
// errors of a DIR that cannot serve (missing, of another scene, with refinement).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

const std::string kRebakeScenes = RADFARM_SOURCE_DIR "/scenes/";

// The Cornell box in `dir` with its light's Ke times `scale`.
std::string CornellBoxLitBy(const TempDir& dir, double scale) {
  std::filesystem::copy_file(kRebakeScenes + "cornell-box.obj", dir.File("cornell-box.obj"));
  std::ofstream mtl(dir.File("cornell-box.mtl"));
  mtl << "newmtl white\nKd 0.725 0.71 0.68\nnewmtl red\nKd 0.63 0.065 0.05\n"
      << "newmtl green\nKd 0.14 0.45 0.091\nnewmtl light\nKd 0.78 0.78 0.78\n"
      << "Ke " << 17 * scale << " " << 12 * scale << " " << 4 * scale << "\n";
  return dir.File("cornell-box.obj");
}

testing::CommandResult RenderBox(const std::string& scene, const std::string& out,
                                 std::vector<std::string> extra = {},
                                 const std::string& patch_size = "50") {
  std::vector<std::string> args = {RADFARM_CLI_PATH, "render",   scene,         "--out", out,
                                   "--patch-size",   patch_size, "--tolerance", "0.002"};
  args.insert(args.end(), extra.begin(), extra.end());
  return RunCommand(args);
}

// The number after "key": in stats.json.
double StatsNumber(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return -1;
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

double RebakeRaysOf(const std::string& dir) {
  const std::string stats = ReadFile(dir + "/stats.json");
  return StatsNumber(stats, "rays") + StatsNumber(stats, "start_rays");
}

TEST(RebakeCommandTest, DimmedLightRebakesCheaplyWithTheSameBitsOnAnyThreads) {
  TempDir before_scene, after_scene, before, full, one, two;
  ASSERT_EQ(RenderBox(CornellBoxLitBy(before_scene, 1), before.path()).exit_code, kExitOk);
  EXPECT_FALSE(ReadFile(before.File("rebake.bin")).empty());
  const std::string dimmed = CornellBoxLitBy(after_scene, 0.5);
  ASSERT_EQ(RenderBox(dimmed, full.path()).exit_code, kExitOk);
  const auto r1 = RenderBox(dimmed, one.path(), {"--from", before.path(), "--threads", "1"});
  ASSERT_EQ(r1.exit_code, kExitOk) << r1.err;
  EXPECT_NE(r1.out.find("re-bake from " + before.path()), std::string::npos) << r1.out;
  const auto r2 = RenderBox(dimmed, two.path(), {"--from", before.path(), "--threads", "2"});
  ASSERT_EQ(r2.exit_code, kExitOk) << r2.err;
  EXPECT_EQ(ReadFile(one.File("patches.csv")), ReadFile(two.File("patches.csv")));
  EXPECT_EQ(ReadFile(one.File("rebake.bin")), ReadFile(two.File("rebake.bin")));
  // The one light is the change: its start is traced again, the gather is not.
  EXPECT_LT(4 * RebakeRaysOf(one.path()), 3 * RebakeRaysOf(full.path()));
}

// A job file's `from` names the previous render for `render`; the farm refuses it before
// connecting, since it would solve the job in full.
TEST(RebakeCommandTest, JobFileFromServesRenderAndSubmitRefusesIt) {
  TempDir before_scene, after_scene, before, out;
  ASSERT_EQ(RenderBox(CornellBoxLitBy(before_scene, 1), before.path()).exit_code, kExitOk);
  CornellBoxLitBy(after_scene, 2);
  const std::string job = after_scene.File("job.toml");
  std::ofstream(job) << "scene = \"cornell-box.obj\"\nfrom = \"" << before.path() << "\"\n";
  const auto r = RenderBox(job, out.path());
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("re-bake from " + before.path()), std::string::npos) << r.out;
  const auto submitted = RunCommand(
      {RADFARM_CLI_PATH, "--control", after_scene.File("no-master.sock"), "submit", job});
  EXPECT_EQ(submitted.exit_code, kExitBadInput);
  EXPECT_NE(submitted.err.find("the farm does not run re-bakes"), std::string::npos)
      << submitted.err;
}

TEST(RebakeCommandTest, MissingDirectoryIsAnInputError) {
  TempDir scene, out;
  const auto r =
      RenderBox(CornellBoxLitBy(scene, 1), out.path(), {"--from", scene.File("no-such-render")});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("not a directory"), std::string::npos) << r.err;
}

TEST(RebakeCommandTest, DirectoryWithoutASolutionIsAnInputError) {
  TempDir scene, empty, out;
  const auto r = RenderBox(CornellBoxLitBy(scene, 1), out.path(), {"--from", empty.path()});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("no rebake.bin"), std::string::npos) << r.err;
}

TEST(RebakeCommandTest, SolutionOfAnotherSceneIsAnInputError) {
  TempDir scene, other, out;
  ASSERT_EQ(RenderBox(kRebakeScenes + "block-on-floor.obj", other.path()).exit_code, kExitOk);
  const auto r = RenderBox(CornellBoxLitBy(scene, 1), out.path(), {"--from", other.path()});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("another mesh"), std::string::npos) << r.err;
}

TEST(RebakeCommandTest, SolutionOfAnotherMeshingIsAnInputError) {
  TempDir scene, before, out;
  const std::string box = CornellBoxLitBy(scene, 1);
  ASSERT_EQ(RenderBox(box, before.path()).exit_code, kExitOk);
  const auto r = RenderBox(box, out.path(), {"--from", before.path()}, "40");
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("another mesh"), std::string::npos) << r.err;
}

TEST(RebakeCommandTest, BrokenSolutionFileIsAnInputError) {
  TempDir scene, before, out;
  const std::string box = CornellBoxLitBy(scene, 1);
  ASSERT_EQ(RenderBox(box, before.path()).exit_code, kExitOk);
  const std::string bin = ReadFile(before.File("rebake.bin"));
  std::ofstream(before.File("rebake.bin"), std::ios::binary | std::ios::trunc)
      << bin.substr(0, bin.size() - 8);
  const auto r = RenderBox(box, out.path(), {"--from", before.path()});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("not what"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace radfarm
