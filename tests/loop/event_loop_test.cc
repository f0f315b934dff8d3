#include "loop/event_loop.h"

#include <gtest/gtest.h>

#include <memory>
#include <thread>

#include "loop/timer.h"
#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::ExpectClosesClean;

TEST(EventLoopTest, EmptyLoopClosesClean) {
  EventLoop loop;
  EXPECT_TRUE(loop.IsLoopThread());
  loop.Run();  // nothing active: returns at once
  ExpectClosesClean(loop);
  EXPECT_TRUE(loop.Close().ok());  // idempotent
}

TEST(EventLoopTest, CloseRefusesWhileAWrapperHoldsAnOpenHandle) {
  EventLoop loop;
  auto timer = std::make_unique<Timer>(loop);
  const Status status = loop.Close();
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find("timer"), std::string::npos) << status.error();
  EXPECT_FALSE(loop.closed());
  EXPECT_EQ(loop.OpenHandleNames(), std::vector<std::string>{"timer"});
  timer.reset();  // starts closing; Close() runs the loop until the close callback has run
  EXPECT_TRUE(loop.OpenHandleNames().empty());
  ExpectClosesClean(loop);
}

TEST(EventLoopTest, ClosedWrapperReportsClosedOnlyAfterTheCloseCallback) {
  EventLoop loop;
  Timer timer(loop);
  EXPECT_EQ(timer.state(), HandleState::kOpen);
  timer.Close();
  EXPECT_EQ(timer.state(), HandleState::kClosing);
  ASSERT_TRUE(testing::RunUntil(loop, [&] { return timer.state() == HandleState::kClosed; }));
  timer.Close();  // no-op once closed
  ExpectClosesClean(loop);
}

TEST(EventLoopTest, OtherThreadIsNotTheLoopThread) {
  EventLoop loop;
  bool other = true;
  std::thread([&] { other = loop.IsLoopThread(); }).join();
  EXPECT_FALSE(other);
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::loop
