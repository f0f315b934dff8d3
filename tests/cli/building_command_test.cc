// `radfarm building` end to end: it writes a job that `radfarm render` takes, deterministic files,
// clear refusals of bad arguments; the rendered building leaks no rays.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

testing::CommandResult RunBuildingCommand(std::vector<std::string> args) {
  args.insert(args.begin(), {RADFARM_CLI_PATH, "building"});
  return RunCommand(args);
}

double StatsValue(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return NAN;
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

TEST(BuildingCommandTest, WritesAJobThatRendersClosed) {
  TempDir dir;
  const auto made = RunBuildingCommand({"--out", dir.path(), "--rooms", "2x1", "--room-size", "3",
                                        "--windows", "--patch-size", "0.5"});
  ASSERT_EQ(made.exit_code, kExitOk) << made.err;
  EXPECT_NE(made.out.find("(rooms 2, doors 1, lights 10"), std::string::npos) << made.out;
  const auto render = RunCommand({RADFARM_CLI_PATH, "render", dir.File("building.toml"), "--out",
                                  dir.File("out"), "--tolerance", "0.02", "-q"});
  ASSERT_EQ(render.exit_code, kExitOk) << render.err;
  const std::string stats = ReadFile(dir.File("out/stats.json"));
  EXPECT_GT(StatsValue(stats, "rays"), 1e6) << stats;
  EXPECT_EQ(StatsValue(stats, "escaped_rays"), 0) << stats;
  EXPECT_EQ(StatsValue(stats, "patch_size"), 0.5) << stats;
  // Refined by default, where the light asks for it.
  EXPECT_GT(StatsValue(stats, "patches_after_refinement"),
            StatsValue(stats, "patches_before_refinement"))
      << stats;
}

// The job file asks for adaptive refinement at 0.05 unless told otherwise; 0 leaves it out.
TEST(BuildingCommandTest, TheJobRefinesUnlessToldNotTo) {
  TempDir refined, uniform, automatic;
  ASSERT_EQ(RunBuildingCommand({"--out", refined.path()}).exit_code, kExitOk);
  ASSERT_EQ(RunBuildingCommand({"--out", uniform.path(), "--refine-tolerance", "0"}).exit_code,
            kExitOk);
  ASSERT_EQ(RunBuildingCommand(
                {"--out", automatic.path(), "--patch-size", "0", "--refine-tolerance", "0.1"})
                .exit_code,
            kExitOk);
  const std::string a = ReadFile(refined.File("building.toml"));
  EXPECT_NE(a.find("[mesh]\npatch_size = 0.25\nrefine = true\nrefine_tolerance = 0.05\n"),
            std::string::npos)
      << a;
  const std::string b = ReadFile(uniform.File("building.toml"));
  EXPECT_NE(b.find("[mesh]\npatch_size = 0.25\n\n"), std::string::npos) << b;
  EXPECT_EQ(b.find("refine"), std::string::npos) << b;
  const std::string c = ReadFile(automatic.File("building.toml"));
  EXPECT_NE(c.find("[mesh]\nrefine = true\nrefine_tolerance = 0.1\n"), std::string::npos) << c;
  EXPECT_EQ(c.find("patch_size"), std::string::npos) << c;
}

TEST(BuildingCommandTest, SameArgumentsSameFiles) {
  TempDir a, b;
  for (const TempDir* dir : {&a, &b}) {
    ASSERT_EQ(RunBuildingCommand({"--out", dir->path(), "--floors", "2", "--seed", "4"}).exit_code,
              kExitOk);
  }
  for (const char* file : {"building.obj", "building.mtl", "building.toml"}) {
    EXPECT_FALSE(ReadFile(a.File(file)).empty()) << file;
    EXPECT_EQ(ReadFile(a.File(file)), ReadFile(b.File(file))) << file;
  }
}

TEST(BuildingCommandTest, RefusesBadArgumentsNamingThem) {
  TempDir dir;
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--rooms", "0x2"}, "rooms"},
      {{"--rooms", "six"}, "rooms"},
      {{"--room-size", "1x4"}, "room width"},
      {{"--floors", "0"}, "floors"},
      {{"--height", "-3"}, "height"},
      {{"--floors", "100", "--rooms", "100x100"}, "limit"},
      {{"--name", "a/b"}, "name"},
      {{"--lights", "0x3"}, "lights"},
      {{"--lights", "101x1"}, "lights"},
      {{"--refine-tolerance", "-0.1"}, "refine-tolerance"},
  };
  for (const auto& [extra, word] : cases) {
    std::vector<std::string> args = {"--out", dir.path()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = RunBuildingCommand(args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << extra[0] << " " << extra[1];
    EXPECT_NE(r.err.find(word), std::string::npos) << r.err;
  }
  const auto missing = RunBuildingCommand({"--rooms", "2x2"});
  EXPECT_EQ(missing.exit_code, kExitBadInput);
  EXPECT_NE(missing.err.find("--out"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace radfarm
