#include "testing/cpu_cap.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm::testing {
namespace {

// The tests need a cpu controller this process may write; without one they skip, saying so.
#define REQUIRE_CPU_CONTROLLER(cpu)                                 \
  std::string why;                                                  \
  const std::optional<CpuController> cpu = FindCpuController(&why); \
  if (!cpu) GTEST_SKIP() << "skipped: " << why

TEST(CpuGroupTest, ACommandRunsInItsGroupWhichIsRemovedAfter) {
  REQUIRE_CPU_CONTROLLER(cpu);
  std::string path;
  {
    const CpuGroup group(*cpu, "test", 0.3);
    path = group.path();
    ASSERT_TRUE(std::filesystem::is_directory(path));
    const CommandResult r =
        RunCommandWith({"/bin/cat", "/proc/self/cgroup"}, {.cgroup_procs = group.procs_path()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::string name = std::filesystem::path(path).filename();
    EXPECT_NE(r.out.find("/" + name + "\n"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(CpuGroupTest, ABusyChildGetsAboutItsShareOfACore) {
  REQUIRE_CPU_CONTROLLER(cpu);
  const TempDir dir;
  std::string path;
  {
    const CpuGroup group(*cpu, "busy", 0.3);
    path = group.path();
    ChildProcess busy({"/bin/sh", "-c", "while :; do :; done"}, dir.File("busy.log"),
                      {.cgroup_procs = group.procs_path()});
    // Uncapped, the loop uses a CPU second a second; capped at 0.3 it takes over three seconds of
    // wall time to use one.
    const auto start = std::chrono::steady_clock::now();
    ASSERT_TRUE(WaitUntil([&] { return ProcessCpuSeconds(busy.pid()).value_or(0) >= 0.6; },
                          std::chrono::seconds(60)));
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu_seconds = ProcessCpuSeconds(busy.pid()).value_or(0);
    busy.Kill();
    EXPECT_LT(cpu_seconds / wall, 0.6) << cpu_seconds << " CPU s in " << wall << " s";
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(CpuGroupTest, RefusesAShareBelowTheSmallestCap) {
  REQUIRE_CPU_CONTROLLER(cpu);
  EXPECT_THROW(CpuGroup(*cpu, "tiny", 0.05), std::runtime_error);
}

TEST(CpuGroupTest, NamesWhatItFoundOrWhyNot) {
  std::string why;
  const std::optional<CpuController> cpu = FindCpuController(&why);
  if (cpu) {
    EXPECT_TRUE(std::filesystem::is_directory(cpu->parent)) << cpu->parent;
    EXPECT_TRUE(why.empty());
  } else {
    EXPECT_EQ(why.rfind(kNoCpuController, 0), 0u) << why;
  }
}

}  // namespace
}  // namespace radfarm::testing
