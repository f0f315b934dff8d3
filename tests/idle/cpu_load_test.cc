#include "idle/cpu_load.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <ctime>
#include <thread>
#include <vector>

namespace radfarm::idle {
namespace {

double CpuClockSeconds(clockid_t clock) {
  timespec now{};
  clock_gettime(clock, &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

// Spins until this thread has used `seconds` of CPU (not of wall time: a loaded machine only
// makes it take longer).
void SpinThreadFor(double seconds) {
  const double start = CpuClockSeconds(CLOCK_THREAD_CPUTIME_ID);
  volatile uint64_t sink = 0;
  while (CpuClockSeconds(CLOCK_THREAD_CPUTIME_ID) - start < seconds) {
    for (int i = 0; i < 10000; ++i) sink = sink + static_cast<uint64_t>(i);
  }
}

double Seconds(const timeval& t) {
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
}

TEST(CpuLoadTest, ParsesTheAggregateLine) {
  const char* text =
      "cpu  100 20 30 400 50 6 7 8 9 10\n"
      "cpu0 50 10 15 200 25 3 3 4 9 10\n"
      "intr 1234\n";
  Result<CpuTimes> times = ParseProcStat(text);
  ASSERT_TRUE(times.ok()) << times.error();
  EXPECT_EQ(times->busy, 100u + 20 + 30 + 6 + 7 + 8);  // guest time is inside user already
  EXPECT_EQ(times->total, times->busy + 400 + 50);

  Result<CpuTimes> old_kernel = ParseProcStat("cpu  1 2 3 4\n");
  ASSERT_TRUE(old_kernel.ok()) << old_kernel.error();
  EXPECT_EQ(old_kernel->busy, 6u);
  EXPECT_EQ(old_kernel->total, 10u);
}

TEST(CpuLoadTest, RejectsTextWithoutAUsableCpuLine) {
  Result<CpuTimes> none = ParseProcStat("cpu0 1 2 3 4\nintr 5\n");
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error(), "/proc/stat: no 'cpu' line");
  Result<CpuTimes> short_line = ParseProcStat("cpu  1 2 x\n");
  ASSERT_FALSE(short_line.ok());
  EXPECT_EQ(short_line.error(),
            "/proc/stat: the 'cpu' line has 2 numbers, expected at least 4: 'cpu  1 2 x'");
}

TEST(CpuLoadTest, OtherFractionSubtractsOwnTime) {
  const CpuTimes before{100, 400};
  const CpuTimes after{300, 800};  // 4 s of all cores, 2 s busy (100 ticks a second)
  EXPECT_DOUBLE_EQ(*OtherCpuFraction(before, after, 0.5, 100), 1.5 / 4);
  EXPECT_DOUBLE_EQ(*OtherCpuFraction(before, after, 0.0, 100), 0.5);
  EXPECT_DOUBLE_EQ(*OtherCpuFraction(before, after, 2.5, 100), 0.0);  // clamped, not negative
  EXPECT_FALSE(OtherCpuFraction(after, after, 0.0, 100).has_value());
  EXPECT_FALSE(OtherCpuFraction(after, before, 0.0, 100).has_value());
}

// A synthetic load from another process: the busy child's CPU time must show up as other load.
TEST(CpuLoadTest, SeesABusyChildProcess) {
  Result<CpuTimes> before = ReadProcStat();
  if (!before.ok()) GTEST_SKIP() << "no /proc/stat here: " << before.error();
  ProcCpuLoad source;
  EXPECT_FALSE(source.OtherLoad().has_value());  // the first reading is a baseline
  const double own_before = OwnCpuSeconds();

  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    SpinThreadFor(0.5);
    _exit(0);
  }
  int status = 0;
  rusage child_usage{};
  ASSERT_EQ(wait4(child, &status, 0, &child_usage), child);
  ASSERT_TRUE(WIFEXITED(status));
  const double child_seconds = Seconds(child_usage.ru_utime) + Seconds(child_usage.ru_stime);

  Result<CpuTimes> after = ReadProcStat();
  ASSERT_TRUE(after.ok()) << after.error();
  const double hz = static_cast<double>(sysconf(_SC_CLK_TCK));
  const std::optional<double> fraction =
      OtherCpuFraction(*before, *after, OwnCpuSeconds() - own_before, hz);
  ASSERT_TRUE(fraction.has_value());
  const double window_seconds = static_cast<double>(after->total - before->total) / hz;
  const double other_seconds = *fraction * window_seconds;
  // Everything the child did lies inside the window; tick accounting is coarse, hence the slack.
  EXPECT_GE(other_seconds, 0.8 * child_seconds - 0.05)
      << "child used " << child_seconds << " s, other load " << *fraction << " of "
      << window_seconds << " s";

  const std::optional<double> load = source.OtherLoad();
  ASSERT_TRUE(load.has_value()) << source.detail();
  EXPECT_GT(*load, 0.0);
  EXPECT_LE(*load, 1.0);
}

// The agent's own render threads are not "other" load.
TEST(CpuLoadTest, OwnBusyThreadsCountAsOwnTime) {
  Result<CpuTimes> before = ReadProcStat();
  if (!before.ok()) GTEST_SKIP() << "no /proc/stat here: " << before.error();
  const double own_before = OwnCpuSeconds();

  constexpr int kThreads = 2;
  constexpr double kSecondsEach = 0.3;
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i) threads.emplace_back(SpinThreadFor, kSecondsEach);
  for (std::thread& thread : threads) thread.join();

  Result<CpuTimes> after = ReadProcStat();
  ASSERT_TRUE(after.ok()) << after.error();
  const double own = OwnCpuSeconds() - own_before;
  EXPECT_GE(own, kThreads * kSecondsEach * 0.95);

  const double hz = static_cast<double>(sysconf(_SC_CLK_TCK));
  const double busy = static_cast<double>(after->busy - before->busy) / hz;
  const double window = static_cast<double>(after->total - before->total) / hz;
  const std::optional<double> fraction = OtherCpuFraction(*before, *after, own, hz);
  ASSERT_TRUE(fraction.has_value());
  // Other load is what the machine did minus our threads' work (up to the clamp at 0).
  EXPECT_NEAR(*fraction * window, std::max(0.0, busy - own), 1e-9);
  EXPECT_LT(*fraction * window, busy);
}

}  // namespace
}  // namespace radfarm::idle
