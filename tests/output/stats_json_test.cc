#include "output/stats_json.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

SolveStats SomeStats() {
  SolveStats stats;
  stats.rays = 18446744073709551615ull;
  stats.start_rays = 7;
  stats.start_seconds = 0.75;
  stats.rounds = 12;
  stats.seconds = 1.25;
  stats.rays_per_second = 0.1;
  stats.patches = 4096;
  stats.unshot_fraction = 9.5e-4;
  stats.escaped_rays = 3;
  stats.backface_hits = 4;
  stats.threads = 2;
  stats.seed = 42;
  stats.sampler = "sobol";
  stats.stop_reason = "converged";
  stats.emitted_power = 100;
  stats.absorbed_power = 99.5;
  stats.escaped_power = NAN;
  return stats;
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(StatsJsonTest, EveryFieldAndExtra) {
  TestDir dir;
  const std::string path = dir.File("stats.json");
  ASSERT_TRUE(WriteStatsJson(path, SomeStats(), {{"mesh_seconds", 0.5}, {"big", INFINITY}}).ok());
  const std::string text = ReadFileBytes(path);
  for (const char* key :
       {"rays", "start_rays", "start_seconds", "rounds", "seconds", "rays_per_second", "patches",
        "unshot_fraction", "escaped_rays", "backface_hits", "threads", "seed", "sampler",
        "stop_reason", "emitted_power", "absorbed_power", "escaped_power", "mesh_seconds", "big"}) {
    EXPECT_TRUE(Contains(text, "\"" + std::string(key) + "\": ")) << key << "\n" << text;
  }
  EXPECT_TRUE(Contains(text, "\"rays\": 18446744073709551615,")) << text;
  EXPECT_TRUE(Contains(text, "\"rays_per_second\": 0.1,")) << text;
  EXPECT_TRUE(Contains(text, "\"start_seconds\": 0.75,")) << text;
  EXPECT_TRUE(Contains(text, "\"unshot_fraction\": 0.00095,")) << text;
  EXPECT_TRUE(Contains(text, "\"sampler\": \"sobol\",")) << text;
  EXPECT_TRUE(Contains(text, "\"escaped_power\": null,")) << text;
  EXPECT_TRUE(Contains(text, "\"big\": null\n}")) << text;
  EXPECT_EQ(text.front(), '{');
  EXPECT_EQ(text.substr(text.size() - 2), "}\n");
  EXPECT_FALSE(Contains(text, "nan"));
  EXPECT_FALSE(Contains(text, "inf"));
}

// A job's timeline, last, one object per phase and place.
TEST(StatsJsonTest, TheTimelineIsAnArrayOfPhases) {
  JobTimeline timeline;
  AddToTimeline(&timeline, JobPhase::kMeshing, kRanOnMaster, 0.5, 0.25);
  AddToTimeline(&timeline, JobPhase::kGather, kRanOnAgents, 0, 12);
  Result<std::string> text = FormatStatsJson(SomeStats(), {{"x", 1}}, {}, timeline);
  ASSERT_TRUE(text.ok()) << text.error();
  EXPECT_TRUE(Contains(*text,
                       "\"x\": 1,\n  \"timeline\": [\n"
                       "    {\"phase\": \"meshing\", \"where\": \"master\", \"wall_seconds\": 0.5, "
                       "\"cpu_seconds\": 0.25},\n"
                       "    {\"phase\": \"gather\", \"where\": \"agents\", \"wall_seconds\": 0, "
                       "\"cpu_seconds\": 12}\n  ]\n}\n"))
      << *text;
  // None: no key.
  EXPECT_FALSE(Contains(*FormatStatsJson(SomeStats(), {}), "timeline"));
}

TEST(StatsJsonTest, EscapesStrings) {
  EXPECT_EQ(JsonString("plain"), "\"plain\"");
  EXPECT_EQ(JsonString("q\"b\\s/"), "\"q\\\"b\\\\s/\"");
  EXPECT_EQ(JsonString("\n\t\r\b\f"), "\"\\n\\t\\r\\b\\f\"");
  EXPECT_EQ(JsonString(std::string("\x01\x1f\x7f", 3)), "\"\\u0001\\u001f\\u007f\"");
  EXPECT_EQ(JsonString(std::string("a\0b", 3)), "\"a\\u0000b\"");
  EXPECT_EQ(JsonString("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"),
            "\"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80\"");  // valid UTF-8 passes through
  EXPECT_EQ(JsonString("bad\xff\xc3"), "\"bad\\ufffd\\ufffd\"");
  EXPECT_EQ(JsonString("\xc0\xaf"), "\"\\ufffd\\ufffd\"");             // overlong '/'
  EXPECT_EQ(JsonString("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // surrogate

  SolveStats stats = SomeStats();
  stats.stop_reason = "time \"budget\"\n";
  const Result<std::string> text = FormatStatsJson(stats, {{"odd\"key", 1}});
  ASSERT_TRUE(text.ok());
  EXPECT_TRUE(Contains(*text, "\"stop_reason\": \"time \\\"budget\\\"\\n\",")) << *text;
  EXPECT_TRUE(Contains(*text, "\"odd\\\"key\": 1")) << *text;
}

TEST(StatsJsonTest, DuplicateKeysAreRejected) {
  EXPECT_FALSE(FormatStatsJson(SomeStats(), {{"seed", 1}}).ok());
  EXPECT_FALSE(FormatStatsJson(SomeStats(), {{"x", 1}, {"x", 2}}).ok());
}

TEST(StatsJsonTest, MissingDirectoryNamesThePath) {
  TestDir dir;
  const std::string path = dir.File("gone/stats.json");
  const Status status = WriteStatsJson(path, SomeStats(), {});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(path), std::string::npos) << status.error();
}

}  // namespace
}  // namespace radfarm
