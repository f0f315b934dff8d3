#include "loop/timer.h"

#include <gtest/gtest.h>

#include <memory>

#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using std::chrono::milliseconds;
using testing::ExpectClosesClean;
using testing::RunUntil;

TEST(TimerTest, OneShotFiresOnceAfterItsTimeout) {
  EventLoop loop;
  Timer timer(loop);
  int fired = 0;
  const uint64_t start = loop.NowMs();
  uint64_t fired_at = 0;
  timer.Start(milliseconds(20), [&] {
    ++fired;
    fired_at = loop.NowMs();
  });
  EXPECT_TRUE(timer.active());
  loop.Run();  // the only active handle: Run returns once it has fired
  EXPECT_EQ(fired, 1);
  EXPECT_GE(fired_at - start, 20u);
  EXPECT_FALSE(timer.active());
  timer.Close();
  ExpectClosesClean(loop);
}

TEST(TimerTest, RepeatsUntilStopped) {
  EventLoop loop;
  Timer timer(loop);
  int fired = 0;
  timer.Start(milliseconds(1), milliseconds(1), [&] {
    if (++fired == 5) timer.Stop();
  });
  loop.Run();
  EXPECT_EQ(fired, 5);
  timer.Close();
  ExpectClosesClean(loop);
}

TEST(TimerTest, CallbackMayRestartItselfWithANewCallback) {
  EventLoop loop;
  Timer timer(loop);
  std::vector<int> order;
  timer.Start(milliseconds(1), [&] {
    order.push_back(1);
    timer.Start(milliseconds(1), [&] { order.push_back(2); });
  });
  loop.Run();
  EXPECT_EQ(order, (std::vector<int>{1, 2}));
  timer.Close();
  ExpectClosesClean(loop);
}

TEST(TimerTest, CallbackMayDestroyItsOwnTimer) {
  EventLoop loop;
  auto timer = std::make_unique<Timer>(loop);
  int fired = 0;
  timer->Start(milliseconds(1), milliseconds(1), [&] {
    ++fired;
    timer.reset();  // frees the wrapper; the handle's memory goes in its close callback
  });
  loop.Run();
  EXPECT_EQ(fired, 1);
  ExpectClosesClean(loop);
}

TEST(TimerTest, CloseStopsATimerBeforeItFires) {
  EventLoop loop;
  Timer timer(loop);
  bool fired = false;
  timer.Start(milliseconds(0), [&] { fired = true; });
  timer.Close();
  loop.Run();
  EXPECT_FALSE(fired);
  EXPECT_EQ(timer.state(), HandleState::kClosed);
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::loop
