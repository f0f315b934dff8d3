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
