#include "loop/work_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>

#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::ExpectClosesClean;
using testing::RunUntil;
using ShutdownMode = WorkQueue::ShutdownMode;

// Holds workers inside their work until Open().
class Gate {
 public:
  void Wait() {
    std::unique_lock lock(mutex_);
    ++waiting_;
    changed_.notify_all();
    changed_.wait(lock, [this] { return open_; });
  }
  bool WaitForWaiters(int count) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, testing::kTimeout, [&] { return waiting_ >= count; });
  }
  void Open() {
    std::lock_guard lock(mutex_);
    open_ = true;
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  int waiting_ = 0;
  bool open_ = false;
};

std::unique_ptr<WorkQueue> MakeQueue(EventLoop& loop, unsigned threads) {
  Result<std::unique_ptr<WorkQueue>> queue = WorkQueue::Create(loop, threads, "test-work");
  EXPECT_TRUE(queue.ok()) << queue.error();
  return queue.ok() ? std::move(queue).value() : nullptr;
}

TEST(WorkQueueTest, ManyItemsRunOnWorkersAndDeliverOnTheLoopThread) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 4);
  const std::thread::id loop_thread = std::this_thread::get_id();
  constexpr int kItems = 2000;
  std::vector<int> results(kItems, -1);
  int delivered = 0;
  bool done_on_loop_thread = true;
  std::atomic<bool> work_on_loop_thread{false};
  for (int i = 0; i < kItems; ++i) {
    ASSERT_TRUE(queue
                    ->Submit(
                        [i, loop_thread, &work_on_loop_thread] {
                          if (std::this_thread::get_id() == loop_thread) work_on_loop_thread = true;
                          return i * 3;
                        },
                        [&, i](Result<int> result) {
                          done_on_loop_thread =
                              done_on_loop_thread && std::this_thread::get_id() == loop_thread;
                          ASSERT_TRUE(result.ok()) << result.error();
                          results[i] = *result;
                          ++delivered;
                        })
                    .ok());
  }
  ASSERT_TRUE(RunUntil(loop, [&] { return delivered == kItems; }));
  EXPECT_TRUE(done_on_loop_thread);
  EXPECT_FALSE(work_on_loop_thread);
  for (int i = 0; i < kItems; ++i) ASSERT_EQ(results[i], i * 3);
  bool shut = false;
  queue->Shutdown(ShutdownMode::kDrain, [&] { shut = true; });
  ASSERT_TRUE(RunUntil(loop, [&] { return shut; }));
  EXPECT_EQ(queue->state(), HandleState::kClosed);
  queue.reset();
  ExpectClosesClean(loop);
}

// Workers Send() once per item, but libuv merges wake-ups: with the loop not running, all of them
// collapse into one, and a single loop iteration must still deliver every result.
TEST(WorkQueueTest, OneMergedWakeUpDrainsTheWholeCompletionQueue) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 2);
  constexpr size_t kItems = 500;
  size_t delivered = 0;
  for (size_t i = 0; i < kItems; ++i) {
    ASSERT_TRUE(queue->Submit([] { return Ok{}; }, [&](Status) { ++delivered; }).ok());
  }
  // Wait, without running the loop, until every item has finished on the workers.
  ASSERT_TRUE(testing::WaitFor([&] { return queue->undelivered() == kItems; }));
  EXPECT_EQ(delivered, 0u);
  loop.RunOnce();
  EXPECT_EQ(delivered, kItems);
  queue.reset();
  ExpectClosesClean(loop);
}

TEST(WorkQueueTest, ResultTypedWorkPassesItsErrorStraightThrough) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 1);
  std::optional<Result<std::string>> got;
  ASSERT_TRUE(queue
                  ->Submit([]() -> Result<std::string> { return Error{"disk full"}; },
                           [&](Result<std::string> result) { got = std::move(result); })
                  .ok());
  ASSERT_TRUE(RunUntil(loop, [&] { return got.has_value(); }));
  ASSERT_FALSE(got->ok());
  EXPECT_EQ(got->error(), "disk full");
  queue.reset();
  ExpectClosesClean(loop);
}

TEST(WorkQueueTest, MoveOnlyCapturesAndResultsWork) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 1);
  auto input = std::make_unique<int>(41);
  int got = 0;
  ASSERT_TRUE(queue
                  ->Submit([input = std::move(input)] { return std::make_unique<int>(*input + 1); },
                           [&](Result<std::unique_ptr<int>> result) { got = **result; })
                  .ok());
  ASSERT_TRUE(RunUntil(loop, [&] { return got != 0; }));
  EXPECT_EQ(got, 42);
  queue.reset();
  ExpectClosesClean(loop);
}

TEST(WorkQueueTest, WorkThatThrowsDeliversAnError) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 1);
  std::optional<std::string> error;
  ASSERT_TRUE(
      queue
          ->Submit([]() -> int { throw std::runtime_error("boom"); },
                   [&](Result<int> result) { error = result.ok() ? "no error" : result.error(); })
          .ok());
  ASSERT_TRUE(RunUntil(loop, [&] { return error.has_value(); }));
  EXPECT_NE(error->find("work threw: boom"), std::string::npos) << *error;
  queue.reset();
  ExpectClosesClean(loop);
}

// Two items block on a gate (one per worker) while more wait behind them; a kCancel shutdown
// fails the waiting ones, lets the running ones finish, and calls every done exactly once.
TEST(WorkQueueTest, CancelShutdownWithPendingWorkIsClean) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 2);
  Gate gate;
  constexpr int kItems = 50;
  std::vector<int> calls(kItems, 0);
  int ok = 0;
  int cancelled = 0;
  for (int i = 0; i < kItems; ++i) {
    ASSERT_TRUE(queue
                    ->Submit(
                        [&gate, i] {
                          if (i < 2) gate.Wait();
                          return i;
                        },
                        [&, i](Result<int> result) {
                          ++calls[i];
                          if (result.ok()) {
                            ++ok;
                          } else {
                            EXPECT_NE(result.error().find("cancelled"), std::string::npos);
                            ++cancelled;
                          }
                        })
                    .ok());
  }
  ASSERT_TRUE(gate.WaitForWaiters(2));  // both workers are busy; 48 items are still queued
  bool shut = false;
  queue->Shutdown(ShutdownMode::kCancel, [&] { shut = true; });
  EXPECT_EQ(queue->state(), HandleState::kClosing);
  EXPECT_FALSE(queue->Submit([] { return 0; }, [](Result<int>) {}).ok());
  gate.Open();
  ASSERT_TRUE(RunUntil(loop, [&] { return shut; }));
  EXPECT_EQ(ok, 2);
  EXPECT_EQ(cancelled, kItems - 2);
  for (int i = 0; i < kItems; ++i) EXPECT_EQ(calls[i], 1) << "item " << i;
  EXPECT_EQ(queue->state(), HandleState::kClosed);
  queue.reset();
  ExpectClosesClean(loop);
}

TEST(WorkQueueTest, DrainShutdownFinishesEveryQueuedItem) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 2);
  Gate gate;
  int ok = 0;
  for (int i = 0; i < 20; ++i) {
    ASSERT_TRUE(queue
                    ->Submit(
                        [&gate, i] {
                          if (i == 0) gate.Wait();
                          return i;
                        },
                        [&](Result<int> result) { ok += result.ok(); })
                    .ok());
  }
  ASSERT_TRUE(gate.WaitForWaiters(1));
  bool shut = false;
  queue->Shutdown(ShutdownMode::kDrain, [&] { shut = true; });
  gate.Open();
  ASSERT_TRUE(RunUntil(loop, [&] { return shut; }));
  EXPECT_EQ(ok, 20);
  queue.reset();
  ExpectClosesClean(loop);
}

TEST(WorkQueueTest, OnShutdownMayDestroyTheQueue) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 3);
  int ok = 0;
  for (int i = 0; i < 100; ++i) {
    ASSERT_TRUE(queue->Submit([] { return 1; }, [&](Result<int> r) { ok += r.ok(); }).ok());
  }
  queue->Shutdown(ShutdownMode::kDrain, [&] { queue.reset(); });
  ASSERT_TRUE(RunUntil(loop, [&] { return queue == nullptr; }));
  EXPECT_EQ(ok, 100);
  ExpectClosesClean(loop);
}

TEST(WorkQueueTest, ADoneMayDestroyTheQueueAndTheRestAreDropped) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 2);
  int delivered = 0;
  for (int i = 0; i < 100; ++i) {
    ASSERT_TRUE(queue
                    ->Submit([] { return 1; },
                             [&](Result<int>) {
                               ++delivered;
                               queue.reset();  // joins the workers; later dones are dropped
                             })
                    .ok());
  }
  ASSERT_TRUE(RunUntil(loop, [&] { return queue == nullptr; }));
  EXPECT_EQ(delivered, 1);
  ExpectClosesClean(loop);
}

// Counts the live copies' owners down when the work closure holding it is destroyed.
struct DropTracker {
  explicit DropTracker(std::atomic<int>* alive) : alive(alive) {}
  DropTracker(DropTracker&& other) noexcept : alive(std::exchange(other.alive, nullptr)) {}
  DropTracker(const DropTracker&) = delete;
  ~DropTracker() {
    if (alive) --*alive;
  }
  std::atomic<int>* alive;
};

TEST(WorkQueueTest, DestroyingWithQueuedWorkJoinsAndDropsIt) {
  EventLoop loop;
  auto queue = MakeQueue(loop, 1);
  Gate gate;
  std::atomic<int> ran{0};
  std::atomic<int> queued_alive{9};
  int delivered = 0;
  for (int i = 0; i < 10; ++i) {
    auto work = [&, i] {
      if (i == 0) gate.Wait();
      return ++ran;
    };
    if (i == 0) {
      ASSERT_TRUE(queue->Submit(work, [&](Result<int>) { ++delivered; }).ok());
    } else {
      ASSERT_TRUE(queue
                      ->Submit([work, tracker = DropTracker(&queued_alive)] { return work(); },
                               [&](Result<int>) { ++delivered; })
                      .ok());
    }
  }
  ASSERT_TRUE(gate.WaitForWaiters(1));
  // The destructor drops the 9 queued items, then waits for the running one: let it finish only
  // once the drop has happened, so no queued item can start.
  std::thread opener([&] {
    ASSERT_TRUE(testing::WaitFor([&] { return queued_alive.load() == 0; }));
    gate.Open();
  });
  queue.reset();
  opener.join();
  EXPECT_EQ(ran.load(), 1);
  EXPECT_EQ(delivered, 0);
  ExpectClosesClean(loop);
}

TEST(WorkQueueTest, ThreadCountIsChecked) {
  EventLoop loop;
  EXPECT_FALSE(WorkQueue::Create(loop, 0, "zero").ok());
  EXPECT_FALSE(WorkQueue::Create(loop, 5000, "many").ok());
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::loop
