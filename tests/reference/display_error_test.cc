// The display read back from the real PLY writer, looked up at points, and the error summary.
#include "reference/display_error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "output/ply_writer.h"
#include "reference/display_lookup.h"
#include "reference/display_ply.h"

namespace radfarm::reference {
namespace {

TEST(DisplayErrorTest, ReadsThePlyWriterAndInterpolatesTheFacingSide) {
  // A unit square at z = 0 as two sides: up (vertex radiance 1, 2, 3, 4 by corner) and down (10).
  DisplayMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.radiance = {{1, 1, 1},    {2, 2, 2},    {3, 3, 3},    {4, 4, 4},
                   {10, 10, 10}, {10, 10, 10}, {10, 10, 10}, {10, 10, 10}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}};
  mesh.triangle_patch = {0, 0, 1, 1};
  mesh.patch_front_only = {true, true};
  Camera camera;
  camera.auto_exposure = false;
  const std::string path = ::testing::TempDir() + "/display_error_test.ply";
  ASSERT_TRUE(WritePly(path, mesh, camera));
  auto ply = ReadDisplayPly(path);
  ASSERT_TRUE(ply) << ply.error();
  EXPECT_EQ(ply->triangles.size(), 4u);
  const DisplayLookup lookup(std::move(*ply), 1e-3);
  // (0.75, 0.25) lies in triangle (0, 1, 2): 1 * 0.25 + 2 * 0.5 + 3 * 0.25.
  const std::optional<Rgb> up = lookup.RadianceAt({0.75, 0.25, 0}, {0, 0, 1});
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->g, 2, 1e-6);
  const std::optional<Rgb> down = lookup.RadianceAt({0.75, 0.25, 0}, {0, 0, -1});
  ASSERT_TRUE(down);
  EXPECT_NEAR(down->g, 10, 1e-6);
  EXPECT_FALSE(lookup.RadianceAt({0.5, 0.5, 0.1}, {0, 0, 1}));  // off the surface
  std::filesystem::remove(path);
}

TEST(DisplayErrorTest, ReadingRefusesAnotherPly) {
  const std::string path = ::testing::TempDir() + "/display_error_test_ascii.ply";
  {
    std::ofstream out(path);
    out << "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n";
  }
  EXPECT_FALSE(ReadDisplayPly(path));
  std::filesystem::remove(path);
}

PointScore Score(double reference, std::optional<double> display) {
  PointScore p;
  p.reference.radiance = {reference, 0, 0};
  if (display) p.display = Rgb{*display, 0, 0};
  return p;
}

TEST(DisplayErrorTest, SummaryLeavesOutDarkAndUnfoundPoints) {
  std::vector<PointScore> scores;
  for (int i = 0; i < 19; ++i) scores.push_back(Score(1, 1 + 0.01 * i));  // 0% .. 18%
  scores.push_back(Score(1, 0.5));                                        // -50%
  scores.push_back(Score(1e-4, 1));                                       // dark
  scores.push_back(Score(1, std::nullopt));                               // unfound
  scores.push_back(Score(0, std::nullopt));  // dark, and not displayed (under a block)
  const ErrorSummary s = ScoreDisplay(&scores);
  EXPECT_EQ(s.points, 23u);
  EXPECT_EQ(s.scored, 20u);
  EXPECT_EQ(s.dark, 2u);
  EXPECT_EQ(s.unfound, 1u);
  EXPECT_NEAR(s.median, 0.09, 1e-12);
  EXPECT_NEAR(s.p95, 0.18, 1e-12);
  EXPECT_NEAR(s.worst, 0.5, 1e-12);
  EXPECT_EQ(s.worst_point, 19);
  EXPECT_NEAR(s.mean_bias, (0.01 * 171 - 0.5) / 20, 1e-12);
  EXPECT_TRUE(scores[20].dark);
}

TEST(DisplayErrorTest, ASubsetIsSummarisedByTheWholeSetsDarkness) {
  std::vector<PointScore> scores;
  for (int i = 0; i < 10; ++i) scores.push_back(Score(1, 1 + 0.01 * i));  // 0% .. 9%
  scores.push_back(Score(1e-4, 1));  // dark against the whole set's median
  scores.push_back(Score(1, 0.7));   // -30%
  ScoreDisplay(&scores);
  // The odd ones: 1%, 3%, 5%, 7%, 9%, and the last two.
  std::vector<bool> keep(scores.size(), false);
  for (size_t i = 1; i < scores.size(); i += 2) keep[i] = true;
  const ErrorSummary s = SummarizeScores(scores, keep);
  EXPECT_EQ(s.points, 6u);
  EXPECT_EQ(s.scored, 6u);  // the dark point is index 10: not kept
  EXPECT_EQ(s.dark, 0u);
  EXPECT_NEAR(s.median, 0.05, 1e-12);
  EXPECT_NEAR(s.worst, 0.3, 1e-12);
  EXPECT_EQ(s.worst_point, 11);
  EXPECT_NEAR(s.mean_bias, (0.01 + 0.03 + 0.05 + 0.07 + 0.09 - 0.3) / 6, 1e-12);
  keep.assign(scores.size(), false);
  keep[10] = true;
  EXPECT_EQ(SummarizeScores(scores, keep).dark, 1u);
  EXPECT_EQ(SummarizeScores(scores, keep).scored, 0u);
}

}  // namespace
}  // namespace radfarm::reference
