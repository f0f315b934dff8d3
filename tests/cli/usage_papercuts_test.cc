// Command-line papercuts: each message names what is wrong, and the CLI refuses
// what the job file refuses in the same words. Runs the real binary.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

using testing::RunCommand;
using testing::TempDir;

const std::string kPapercutScenes = RADFARM_SOURCE_DIR "/scenes/";

bool Mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Was: "A subcommand is required".
TEST(UsagePapercutsTest, AnUnknownSubcommandIsNamed) {
  const auto r = RunCommand({RADFARM_CLI_PATH, "bogus"});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_TRUE(Mentions(r.err, "radfarm: unknown subcommand 'bogus'")) << r.err;
  EXPECT_TRUE(Mentions(r.err, "render")) << r.err;  // the list of what there is
  EXPECT_FALSE(Mentions(r.err, "required")) << r.err;
}

TEST(UsagePapercutsTest, AnUnknownSubcommandAfterTheControlOptionIsNamed) {
  const auto r = RunCommand({RADFARM_CLI_PATH, "--control", "/nonexistent.sock", "stauts", "1"});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_TRUE(Mentions(r.err, "unknown subcommand 'stauts'")) << r.err;
}

// Was: "--out is required".
TEST(UsagePapercutsTest, AnUnknownOptionIsNamedBeforeMissingRequiredOnes) {
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", "--bogus", "x"});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_TRUE(Mentions(r.err, "--bogus")) << r.err;
  EXPECT_FALSE(Mentions(r.err, "--out is required")) << r.err;
}

TEST(UsagePapercutsTest, AMissingRequiredOptionIsStillReported) {
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", kPapercutScenes + "furnace.obj"});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_TRUE(Mentions(r.err, "--out is required")) << r.err;
}

// Was: the CLI took --tolerance 1, which the job file refuses.
TEST(UsagePapercutsTest, ToleranceOneIsRefusedOnTheCommandLineAsInTheJobFile) {
  TempDir dir;
  for (const char* command : {"render", "submit"}) {
    std::vector<std::string> args = {RADFARM_CLI_PATH, command, kPapercutScenes + "furnace.obj",
                                     "--tolerance", "1"};
    if (std::string(command) == "render") args.insert(args.end(), {"--out", dir.path()});
    const auto r = RunCommand(args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << command;
    EXPECT_TRUE(Mentions(r.err, "--tolerance: must be in (0, 1), got 1"))
        << command << ": " << r.err;
  }
  const std::string job = dir.path() + "/tolerance.toml";
  std::ofstream(job) << "scene = \"" << kPapercutScenes
                     << "furnace.obj\"\n[solver]\ntolerance = 1\n";
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", job, "--out", dir.path()});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_TRUE(Mentions(r.err, "'solver.tolerance' must be in (0, 1), got 1")) << r.err;
}

TEST(UsagePapercutsTest, ToleranceInsideTheRangeIsTaken) {
  TempDir dir;
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", kPapercutScenes + "furnace.obj", "--out",
                             dir.path(), "--tolerance", "0.5", "--quiet"});
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
}

TEST(UsagePapercutsTest, AToleranceThatIsNoNumberIsNamed) {
  TempDir dir;
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", kPapercutScenes + "furnace.obj", "--out",
                             dir.path(), "--tolerance", "small"});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_TRUE(Mentions(r.err, "--tolerance: must be a number, got 'small'")) << r.err;
}

// "--seed -1" and seeds past 2^64 became 2^64 - 1; "--max-memory -1" meant no limit.
TEST(UsagePapercutsTest, NumbersOutOfRangeAreRefusedNotWrapped) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"--seed", "-1"},      {"--seed", "18446744073709551616"},     {"--max-memory", "-1"},
      {"--max-memory", "0"}, {"--max-memory", "20000000000000000T"}, {"--max-scene-bytes", "-1"}};
  for (const auto& [option, value] : refused) {
    for (const char* command : {"render", "submit"}) {
      std::vector<std::string> args = {RADFARM_CLI_PATH, command, kPapercutScenes + "furnace.obj",
                                       option, value};
      if (std::string(command) == "render") args.insert(args.end(), {"--out", dir.path()});
      const auto r = RunCommand(args);
      EXPECT_EQ(r.exit_code, kExitBadInput) << command << " " << option << " " << value;
      EXPECT_TRUE(Mentions(r.err, option)) << r.err;
      EXPECT_TRUE(Mentions(r.err, "'" + value + "'")) << r.err;
    }
  }
  const auto building = RunCommand(
      {RADFARM_CLI_PATH, "building", "--seed", "-1", "--out", dir.path() + "/building.obj"});
  EXPECT_EQ(building.exit_code, kExitBadInput) << building.err;
}

TEST(UsagePapercutsTest, NumbersInRangeAreTaken) {
  TempDir dir;
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", kPapercutScenes + "furnace.obj", "--out",
                             dir.path(), "--tolerance", "0.5", "--quiet", "--seed",
                             "18446744073709551615", "--max-memory", "2GiB"});
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
}

// Was: "default: job-ID", though the master names a job after its scene's OBJ.
TEST(UsagePapercutsTest, SubmitHelpSaysWhatTheDefaultNameIs) {
  const auto r = RunCommand({RADFARM_CLI_PATH, "submit", "--help"});
  EXPECT_EQ(r.exit_code, kExitOk);
  EXPECT_FALSE(Mentions(r.out, "job-ID")) << r.out;
  EXPECT_TRUE(Mentions(r.out, "default: the scene file's name")) << r.out;
}

// Was: SCENE "Wavefront .obj scene or .toml job file", though both read glTF too; and render's
// list of what it writes left out lightmaps/.
TEST(UsagePapercutsTest, RenderAndSubmitHelpNameEveryInputAndOutput) {
  for (const char* command : {"render", "submit"}) {
    const auto r = RunCommand({RADFARM_CLI_PATH, command, "--help"});
    EXPECT_EQ(r.exit_code, kExitOk) << command;
    for (const char* input : {".obj", ".mtl", ".gltf", ".glb", ".toml"}) {
      EXPECT_TRUE(Mentions(r.out, input)) << command << " " << input << ": " << r.out;
    }
  }
  const auto render = RunCommand({RADFARM_CLI_PATH, "render", "--help"});
  for (const char* output : {"image.png", "image.exr", "radiosity.ply", "lit.glb", "lightmaps/",
                             "patches.csv", "stats.json"}) {
    EXPECT_TRUE(Mentions(render.out, output)) << output << ": " << render.out;
  }
}

// Was: "ray budget after 1 rounds".
TEST(UsagePapercutsTest, OneRoundIsSingular) {
  TempDir dir;
  // The grid's shots cannot be cut or paced: a budget below one shot ends the first round.
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", kPapercutScenes + "furnace.obj", "--out",
                             dir.path(), "--rays", "100", "--sampler", "grid"});
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_TRUE(Mentions(r.out, "ray budget after 1 round:")) << r.out;
}

}  // namespace
}  // namespace radfarm
