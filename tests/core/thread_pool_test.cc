#include "core/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

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

}  // namespace
}  // namespace radfarm
