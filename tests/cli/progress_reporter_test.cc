#include "cli/progress_reporter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "core/solve_control.h"

namespace radfarm {
namespace {

TEST(ProgressTest, ConvergenceFractionIsLogarithmic) {
  EXPECT_DOUBLE_EQ(ConvergenceFraction(1.0, 1e-3), 0.0);
  EXPECT_NEAR(ConvergenceFraction(0.1, 1e-3), 1.0 / 3, 1e-12);
  EXPECT_DOUBLE_EQ(ConvergenceFraction(1e-4, 1e-3), 1.0);
}

// What a memstream received.
class Captured {
 public:
  Captured() : file_(open_memstream(&text_, &size_)) {}
  ~Captured() {
    if (file_ != nullptr) fclose(file_);
    free(text_);
  }
  FILE* file() { return file_; }
  std::string Text() {
    fflush(file_);
    return std::string(text_, size_);
  }

 private:
  char* text_ = nullptr;
  size_t size_ = 0;
  FILE* file_;
};

// What `report` makes a reporter write.
std::string Written(bool interactive, const std::function<void(ProgressReporter&)>& report) {
  Captured out;
  ProgressReporter reporter(out.file(), interactive);
  report(reporter);
  return out.Text();
}

std::string Capture(bool interactive, int rounds) {
  return Written(interactive, [&](ProgressReporter& reporter) {
    EnergyAccount energy;
    for (int i = 1; i <= rounds; ++i) {
      reporter.OnRound({uint32_t(i), uint64_t(i) * 1000, i * 2.0, std::pow(0.5, i), 1e-3, &energy});
    }
    reporter.Finish();
  });
}

TEST(ProgressTest, TerminalRedrawsOneLine) {
  const std::string s = Capture(true, 3);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\r'), 3);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1);
  EXPECT_NE(s.find("ETA"), std::string::npos);
}

// A terminal sees every step of the display on its line, erased when done; a log gets the steps
// of many points only (a count, so the log is the same every run).
TEST(ProgressTest, TheDisplaysStepsShow) {
  for (bool interactive : {true, false}) {
    const uint64_t many = ProgressReporter::kDisplayLogPoints;
    const std::string s = Written(interactive, [&](ProgressReporter& reporter) {
      reporter.OnDisplayStep({DisplayStep::kDirectLight, many, 0});
      reporter.OnDisplayStep({DisplayStep::kGathering, many - 1, 0});
      reporter.OnDisplayStep({DisplayStep::kRefining, many + 5, 2});
      reporter.ClearLine();
    });
    const std::string direct = "display: direct light at " + std::to_string(many) + " points";
    const std::string refining = "display: " + std::to_string(many + 5) +
                                 " points added where the light bends (level 2 of 3)";
    EXPECT_NE(s.find(direct), std::string::npos) << s;
    EXPECT_NE(s.find(refining), std::string::npos) << s;
    if (interactive) {
      EXPECT_NE(s.find("gathering light at " + std::to_string(many - 1)), std::string::npos) << s;
      EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 0) << s;
      EXPECT_EQ(s.substr(s.size() - 4), "\r\033[K") << "the last line erased";
    } else {
      EXPECT_EQ(s, direct + "\n" + refining + "\n");
    }
  }
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
    const std::string s = Written(interactive, [](ProgressReporter& reporter) {
      EnergyAccount energy;
      reporter.OnRound({1, 1000, 1.0, 1e-4, 1e-3, &energy});
      reporter.OnRound({2, 5000, 2.0, 0, 1e-3, &energy, true});
      reporter.Finish();
    });
    EXPECT_NE(s.find("\nfinal gather: 5000 rays in all"), std::string::npos) << s;
    EXPECT_EQ(s.back(), '\n') << s;
    EXPECT_EQ(s.find("\n\n"), std::string::npos) << s;
  }
}

// A shooting round that reaches the tolerance with the gather still to come, then the gather.
RoundProgress Shooting(uint32_t round, double before, double after, uint64_t rays_total) {
  RoundProgress p{round, rays_total, 1.0 * round, after, 1e-3};
  p.gather_rays_left = 8'000'000;
  p.round_rays = 1'000'000;
  p.round_seconds = 1.0;
  p.unshot_before = before;
  return p;
}

// The bar reached 100% before the final gather, which casts most of a job's rays.
TEST(ProgressTest, TheBarLeavesRoomForTheGather) {
  Captured out;
  ProgressReporter reporter(out.file(), true);
  reporter.OnRound(Shooting(1, 0.01, 5e-4, 1'000'000));
  const std::string s = out.Text();
  const size_t bar = s.rfind('[');
  ASSERT_NE(bar, std::string::npos) << s;
  const std::string cells = s.substr(bar + 1, 30);
  const auto filled = std::count(cells.begin(), cells.end(), '#');
  EXPECT_EQ(filled, 3) << s;                            // 1 M of 9 M rays
  EXPECT_NE(s.find("ETA 8s"), std::string::npos) << s;  // 8 M rays at 1 M rays/s
}

// The gather showed no progress.
TEST(ProgressTest, TheFinalGatherShowsItsProgressOncePerSecondInALog) {
  Captured out;
  ProgressReporter reporter(out.file(), false);
  reporter.OnRound(Shooting(1, 0.01, 5e-4, 1'000'000));
  for (double seconds : {0.5, 1.2, 1.9, 2.5, 3.6}) {
    reporter.OnRoundRunning(
        {2, 8'000'000, uint64_t(seconds / 4 * 8'000'000), seconds, /*gather=*/true});
  }
  reporter.OnRoundRunning({2, 8'000'000, 8'000'000, 4.0, true});
  RoundProgress gather{2, 9'000'000, 5.0, 0, 1e-3};
  gather.gather = true;
  reporter.OnRound(gather);
  reporter.Finish();
  const std::string s = out.Text();
  // At 1.2 s (the first second), 2.5 s and 3.6 s: each a second after the one before. The ETA at
  // 30% blends the gather's own pace (2.8 s left) with the first round's (6.8 s), 0.3 to 0.7.
  EXPECT_EQ(s.find("final gather 12%"), std::string::npos) << s;
  EXPECT_NE(s.find("final gather 30% of 8000000 rays  2.00 Mrays/s  ETA 6s\n"), std::string::npos)
      << s;
  EXPECT_EQ(s.find("final gather 48%"), std::string::npos) << s;
  EXPECT_NE(s.find("final gather 62%"), std::string::npos) << s;
  EXPECT_NE(s.find("final gather 90%"), std::string::npos) << s;
  EXPECT_NE(s.find("\nfinal gather: 9000000 rays in all"), std::string::npos) << s;
}

// A big scene's first round ran 23 s without a line.
TEST(ProgressTest, ALongShootingRoundShowsItsProgressBeforeItsEnd) {
  Captured out;
  ProgressReporter reporter(out.file(), false);
  for (double seconds : {0.4, 1.1, 1.5, 2.4}) {
    reporter.OnRoundRunning({0, 4'000'000, uint64_t(seconds / 4 * 4'000'000), seconds, false});
  }
  const std::string s = out.Text();
  EXPECT_EQ(s.find("round 1 10%"), std::string::npos) << s;  // before the first second
  EXPECT_NE(s.find("round 1 28% of 4000000 rays  1.00 Mrays/s  ETA ?\n"), std::string::npos) << s;
  EXPECT_EQ(s.find("round 1 38%"), std::string::npos) << s;  // under a second after the last
  EXPECT_NE(s.find("round 1 60%"), std::string::npos) << s;
  // The next round starts its own count: its first second prints nothing.
  reporter.OnRoundRunning({1, 1'000'000, 500'000, 0.5, false});
  EXPECT_EQ(out.Text().find("round 2 "), std::string::npos) << out.Text();
}

// The ETA includes the display that follows the solve (a bar said "ETA 1s" before a 24 s
// display): its forecast rays at the rounds' pace.
TEST(ProgressTest, TheEtaIncludesTheDisplay) {
  Captured alone_out, with_out;
  ProgressReporter alone(alone_out.file(), false), with_display(with_out.file(), false);
  RoundProgress round = Shooting(1, 0.01, 5e-4, 1'000'000);
  alone.OnRound(round);
  round.display_rays = 20'000'000;  // 20 s at the round's 1 Mrays/s
  with_display.OnRound(round);
  EXPECT_NE(alone_out.Text().find("ETA 8s\n"), std::string::npos) << alone_out.Text();
  EXPECT_NE(with_out.Text().find("ETA 28s\n"), std::string::npos) << with_out.Text();
}

// Under a time budget the ETA is at most the time the budget leaves the rounds, after a round and
// while one runs (a --seconds 5 render on 88,750 patches showed "ETA 36s").
TEST(ProgressTest, TheEtaKeepsWithinTheBudget) {
  Captured out;
  ProgressReporter reporter(out.file(), false);
  RoundProgress first = Shooting(1, 0.01, 5e-4, 1'000'000);
  first.budget_seconds_left = 3.2;
  reporter.OnRound(first);
  EXPECT_NE(out.Text().find("ETA 4s\n"), std::string::npos) << out.Text();  // not 8 s
  RoundRunning gather{2, 8'000'000, 2'000'000, 1.5, true};
  gather.budget_seconds_left = 1.7;
  reporter.OnRoundRunning(gather);
  EXPECT_NE(out.Text().find("final gather 25% of 8000000 rays  1.33 Mrays/s  ETA 2s\n"),
            std::string::npos)
      << out.Text();
}

TEST(ProgressTest, AShortGatherPrintsNoProgressLines) {
  Captured out;
  ProgressReporter reporter(out.file(), false);
  reporter.OnRound(Shooting(1, 0.01, 5e-4, 1'000'000));
  reporter.OnRoundRunning({2, 8'000'000, 4'000'000, 0.1, true});
  reporter.OnRoundRunning({2, 8'000'000, 8'000'000, 0.2, true});
  EXPECT_EQ(out.Text().find("final gather "), std::string::npos) << out.Text();
}

}  // namespace
}  // namespace radfarm
