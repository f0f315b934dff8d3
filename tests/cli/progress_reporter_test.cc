#include "cli/progress_reporter.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace radfarm {
namespace {

TEST(ProgressTest, ConvergenceFractionIsLogarithmic) {
  EXPECT_DOUBLE_EQ(ConvergenceFraction(1.0, 1e-3), 0.0);
  EXPECT_NEAR(ConvergenceFraction(0.1, 1e-3), 1.0 / 3, 1e-12);
  EXPECT_DOUBLE_EQ(ConvergenceFraction(1e-4, 1e-3), 1.0);
  EXPECT_LT(EstimateSecondsLeft(1.0, 1e-3, 5, 100, 0), 0);  // unknown before any progress
  EXPECT_NEAR(EstimateSecondsLeft(0.1, 1e-3, 2, 100, 0), 4, 1e-9);
}

// The final gather still to come adds its rays at the rate seen so far, also once the shooting
// has converged (it used to read 0 s there, while the gather took most of the time).
TEST(ProgressTest, EtaCountsTheGatherStillToCome) {
  EXPECT_NEAR(EstimateSecondsLeft(0.1, 1e-3, 2, 1000, 500), 4 + 1, 1e-9);
  EXPECT_NEAR(EstimateSecondsLeft(1e-4, 1e-3, 2, 1000, 3000), 6, 1e-9);
  EXPECT_DOUBLE_EQ(EstimateSecondsLeft(1e-4, 1e-3, 2, 1000, 0), 0);
}

std::string Capture(bool interactive, int rounds) {
  char* text = nullptr;
  size_t size = 0;
  FILE* f = open_memstream(&text, &size);
  ProgressReporter reporter(f, interactive);
  EnergyAccount energy;
  for (int i = 1; i <= rounds; ++i) {
    reporter.OnRound({uint32_t(i), uint64_t(i) * 1000, i * 2.0, std::pow(0.5, i), 1e-3, &energy});
  }
  reporter.Finish();
  fclose(f);
  std::string s(text, size);
  free(text);
  return s;
}

TEST(ProgressTest, TerminalRedrawsOneLine) {
  const std::string s = Capture(true, 3);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\r'), 3);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1);
  EXPECT_NE(s.find("ETA"), std::string::npos);
}

TEST(ProgressTest, PipeGetsLogLines) {
  const std::string s = Capture(false, 3);
  EXPECT_EQ(s.find('\r'), std::string::npos);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 3);
  EXPECT_NE(s.find("round 2: unshot 25.0000% of emitted"), std::string::npos) << s;
}

// The final gather gets its own line, after the bar's or the log's last round.
TEST(ProgressTest, TheFinalGatherIsNamed) {
  for (bool interactive : {true, false}) {
    char* text = nullptr;
    size_t size = 0;
    FILE* f = open_memstream(&text, &size);
    ProgressReporter reporter(f, interactive);
    EnergyAccount energy;
    reporter.OnRound({1, 1000, 1.0, 1e-4, 1e-3, &energy});
    reporter.OnRound({2, 5000, 2.0, 0, 1e-3, &energy, true});
    reporter.Finish();
    fclose(f);
    const std::string s(text, size);
    free(text);
    EXPECT_NE(s.find("\nfinal gather: 5000 rays in all"), std::string::npos) << s;
    EXPECT_EQ(s.back(), '\n') << s;
    EXPECT_EQ(s.find("\n\n"), std::string::npos) << s;
  }
}

}  // namespace
}  // namespace radfarm
