#include "core/thread_pool.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace radfarm {
namespace {

TEST(ThreadPoolTest, EveryIndexRunsExactlyOnce) {
  for (unsigned threads : {1u, 2u, 7u}) {
    ThreadPool pool(threads);
    for (int repeat = 0; repeat < 20; ++repeat) {
      std::vector<std::atomic<int>> calls(1000);
      pool.ParallelFor(calls.size(), [&](unsigned worker, size_t i) {
        EXPECT_LT(worker, pool.size());
        calls[i]++;
      });
      for (auto& c : calls) ASSERT_EQ(c.load(), 1);
    }
  }
}

TEST(ThreadPoolTest, ParallelForOrInlineRunsInOrderWithoutAPool) {
  std::vector<size_t> order;
  ParallelForOrInline(nullptr, 5, [&](unsigned worker, size_t i) {
    EXPECT_EQ(worker, 0u);
    order.push_back(i);
  });
  EXPECT_EQ(order, (std::vector<size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(WorkersOf(nullptr), 1u);

  ThreadPool pool(3);
  EXPECT_EQ(WorkersOf(&pool), 3u);
  std::vector<std::atomic<int>> calls(500);
  ParallelForOrInline(&pool, calls.size(), [&](unsigned worker, size_t i) {
    EXPECT_LT(worker, 3u);
    calls[i]++;
  });
  for (auto& c : calls) EXPECT_EQ(c.load(), 1);
}

TEST(ThreadPoolTest, EmptyLoopReturns) {
  ThreadPool pool(3);
  pool.ParallelFor(0, [](unsigned, size_t) { FAIL(); });
}

TEST(ThreadPoolTest, ExceptionIsRethrownAndPoolStaysUsable) {
  ThreadPool pool(2);
  EXPECT_THROW(pool.ParallelFor(100,
                                [](unsigned, size_t i) {
                                  if (i == 50) throw std::runtime_error("boom");
                                }),
               std::runtime_error);
  std::atomic<int> n = 0;
  pool.ParallelFor(10, [&](unsigned, size_t) { n++; });
  EXPECT_EQ(n.load(), 10);
}

// The address space mapped now, from /proc/self/statm.
uint64_t MappedBytes() {
  unsigned long pages = 0;
  FILE* statm = std::fopen("/proc/self/statm", "r");
  if (statm == nullptr) return 0;
  if (std::fscanf(statm, "%lu", &pages) != 1) pages = 0;
  std::fclose(statm);
  return uint64_t{pages} * static_cast<uint64_t>(sysconf(_SC_PAGESIZE));
}

// In a child: a pool of 4096 threads with address space for a few more thread stacks (8 MiB
// each). Exits 3 when the pool throws std::system_error, 0 when it starts them all, 2 when the
// limit cannot be set.
[[noreturn]] void StartMoreThreadsThanTheAddressSpaceHolds() {
  const uint64_t mapped = MappedBytes();
  rlimit limit{};
  limit.rlim_cur = limit.rlim_max = mapped + (64u << 20);
  if (mapped == 0 || setrlimit(RLIMIT_AS, &limit) != 0) std::_Exit(2);
  try {
    ThreadPool pool(4096);
  } catch (const std::system_error&) {
    std::_Exit(3);
  }
  std::_Exit(0);
}

// Hostile scenes, threads: where the system refuses a thread, `render` and `fetch` aborted, since
// the pool's constructor let std::system_error out past the threads it had started (their
// std::thread destructors terminate). Now the exception arrives and the caller reports it.
TEST(ThreadPoolDeathTest, AThreadTheSystemRefusesIsAnExceptionNotAnAbort) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(StartMoreThreadsThanTheAddressSpaceHolds(), ::testing::ExitedWithCode(3), "");
}

}  // namespace
}  // namespace radfarm
