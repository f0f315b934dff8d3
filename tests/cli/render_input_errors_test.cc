// Bad input to `radfarm render`: a one-line error naming the file and the line or key, exit code 2.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

using testing::RunCommand;
using testing::TempDir;

const std::string kData = RADFARM_SOURCE_DIR "/tests/input/data/";

struct BadInput {
  std::string file;
  std::string message;  // must appear in stderr
};

void PrintTo(const BadInput& bad, std::ostream* os) { *os << bad.file; }

class RenderInputErrorTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(RenderInputErrorTest, OneLineErrorNamingTheLocationAndExitTwo) {
  TempDir out;
  const BadInput& bad = GetParam();
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", kData + bad.file, "--out", out.path()});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find(bad.message), std::string::npos) << r.err;
  // The error is the last line of stderr and a single line.
  const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
  EXPECT_EQ(last.find('\n'), last.size() - 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    BadScenes, RenderInputErrorTest,
    ::testing::Values(
        BadInput{"does_not_exist.obj", "does_not_exist.obj: cannot open"},
        BadInput{"garbage.obj", "garbage.obj:4: unknown statement 'hello'"},
        BadInput{"bad_number.obj", "bad_number.obj:3: 'v': cannot parse 'abc' as a number"},
        BadInput{"index_out_of_range.obj",
                 "index_out_of_range.obj:11: vertex index 9 out of range (8 vertices)"},
        BadInput{"nan.obj", "nan.obj:3: 'v': 'nan' is not a finite number"},
        BadInput{"kd_too_high.obj",
                 "kd_too_high.mtl:5: material 'mirror': reflectance Kd 1 0.5 "
                 "0.5 outside [0, 1)"},
        BadInput{"negative_ke.obj",
                 "negative_ke.mtl:4: material 'sink': emission Ke 1 -1 1 is "
                 "negative"},
        BadInput{"no_light.obj", "no_light.obj: nothing to light"},
        BadInput{"jobs/unknown_key.toml", "unknown_key.toml:"},
        BadInput{"jobs/syntax_error.toml", "syntax_error.toml:"},
        BadInput{"jobs/lamp_type_b.toml",
                 "jobs/type_b.ies:4: photometric type 2 (type B) is not supported"}),
    [](const auto& info) {
      std::string name = info.param.file.substr(info.param.file.rfind('/') + 1);
      for (char& c : name) {
        if (!isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

// A job's IES lamp whose file is not there: the job file's line and key, then the file.
TEST(RenderLampErrorTest, AMissingIesFileIsNamedAfterItsJobFileLine) {
  TempDir out;
  const auto r = RunCommand(
      {RADFARM_CLI_PATH, "render", kData + "jobs/lamp_missing_file.toml", "--out", out.path()});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  const size_t at = r.err.find("lamp_missing_file.toml:5: 'lamps[0].file': ");
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("jobs/no_such_lamp.ies: cannot open", at), std::string::npos) << r.err;
}

TEST(RenderUsageTest, BadOptionValuesExitTwo) {
  TempDir out;
  const std::string scene = RADFARM_SOURCE_DIR "/scenes/furnace.obj";
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--sampler", "magic"},
                                                {"--threads", "0"},
                                                {"--tolerance", "-1"},
                                                {"--rays", "many"},
                                                {"--lightmap-size", "8"},
                                                {"--lightmap-size", "8193"},
                                                {"--no-such-option"}}) {
    std::vector<std::string> args = {RADFARM_CLI_PATH, "render", scene, "--out", out.path()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = RunCommand(args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << extra[0] << ": " << r.err;
    EXPECT_NE(r.err.find(extra[0]), std::string::npos) << r.err;
  }
}

// Hostile scenes: a material name with terminal escapes, quoted in a warning, retitled the
// terminal and cleared the screen. Every message the CLI prints is escaped.
TEST(RenderUsageTest, ControlCharactersFromTheSceneArePrintedEscaped) {
  TempDir dir;
  std::ofstream(dir.File("evil.mtl")) << "newmtl light\nKd 0.5 0.5 0.5\nKe 1 1 1\n";
  std::ofstream(dir.File("evil.obj")) << "mtllib evil.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                      << "usemtl light\nf 1 2 3\n"
                                      << "usemtl evil\x1b]0;owned\x07\x1b[2J\xc2\x9b"
                                         "31m\n"
                                      << "f 1 2 4\n";
  const auto r = RunCommand(
      {RADFARM_CLI_PATH, "render", dir.File("evil.obj"), "--out", dir.File("out"), "-q"});
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\x07'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("\xc2\x9b"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("material 'evil\\x1b]0;owned\\x07\\x1b[2J\\u009b31m' not defined"),
            std::string::npos)
      << r.err;
}

TEST(RenderUsageTest, MissingArgumentsExitTwo) {
  EXPECT_EQ(RunCommand({RADFARM_CLI_PATH}).exit_code, kExitBadInput);
  EXPECT_EQ(RunCommand({RADFARM_CLI_PATH, "render"}).exit_code, kExitBadInput);
  EXPECT_EQ(RunCommand({RADFARM_CLI_PATH, "render", "x.obj"}).exit_code, kExitBadInput);
}

TEST(RenderUsageTest, HelpDescribesEveryOption) {
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", "--help"});
  EXPECT_EQ(r.exit_code, kExitOk);
  for (const char* option : {"--out", "--threads", "--seed", "--tolerance", "--rays", "--seconds",
                             "--sampler", "--patch-size", "--camera", "--lightmap-size"}) {
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
  }
  EXPECT_EQ(RunCommand({RADFARM_CLI_PATH, "--help"}).exit_code, kExitOk);
}

TEST(RenderUsageTest, UnwritableOutputDirectoryIsAFailure) {
  TempDir dir;
  const std::string blocker = dir.File("file");
  FILE* f = fopen(blocker.c_str(), "w");
  fclose(f);
  const auto r = RunCommand({RADFARM_CLI_PATH, "render", RADFARM_SOURCE_DIR "/scenes/furnace.obj",
                             "--out", blocker + "/sub", "-q"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find(blocker), std::string::npos) << r.err;
}

// An existing --out directory that could not be written was found only after the solve, when its
// first file failed: it is checked before the solve, and before the mesh summary is printed.
TEST(RenderUsageTest, AnExistingUnwritableOutputDirectoryFailsBeforeTheSolve) {
  TempDir dir;
  std::string out = dir.File("locked");
  if (geteuid() == 0) {
    out = "/proc";  // root writes whatever the mode bits say; no one creates files in /proc
  } else {
    std::filesystem::create_directory(out);
    std::filesystem::permissions(
        out, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  }
  const auto r = RunCommand(
      {RADFARM_CLI_PATH, "render", RADFARM_SOURCE_DIR "/scenes/cornell-box.obj", "--out", out});
  EXPECT_EQ(r.exit_code, kExitFailure) << r.err;
  EXPECT_NE(r.err.find(out + ": cannot write to the output directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

}  // namespace
}  // namespace radfarm

namespace radfarm {
namespace {

// A job too large for the memory limit is refused before meshing, with the estimate and the limit.
TEST(RenderMemoryLimitTest, AJobOverTheLimitIsRefusedWithTheEstimateAndTheLimit) {
  testing::TempDir out;
  const std::string cornell = RADFARM_SOURCE_DIR "/scenes/cornell-box.obj";
  auto r = testing::RunCommand({RADFARM_CLI_PATH, "render", cornell, "--out", out.path(),
                                "--patch-size", "5", "--max-memory", "100M"});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  // The estimate is the mesher's count before welding: 90,547 pieces for 88,747 patches.
  EXPECT_NE(r.err.find("cornell-box.obj: 90547 patches (patch size 5) need about 196 MB of "
                       "memory, more than the limit of 100 MB (--max-memory)"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(out.path()));
  r = testing::RunCommand(
      {RADFARM_CLI_PATH, "render", cornell, "--out", out.path(), "--max-memory", "lots"});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace radfarm
