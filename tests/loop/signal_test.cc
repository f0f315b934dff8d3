#include <gtest/gtest.h>

#include <csignal>

#include "loop/os_signal.h"
#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::ExpectClosesClean;
using testing::RunUntil;

// SIGTERM and SIGINT are what the daemons watch; while a Signal is open they do not kill us.
class SignalTest : public ::testing::TestWithParam<int> {};

TEST_P(SignalTest, RaisedSignalRunsTheCallbackOnTheLoop) {
  EventLoop loop;
  int received = 0;
  Result<std::unique_ptr<Signal>> watch =
      Signal::Watch(loop, GetParam(), [&](int signum) { received = signum; });
  ASSERT_TRUE(watch.ok()) << watch.error();
  ASSERT_EQ(std::raise(GetParam()), 0);
  ASSERT_TRUE(RunUntil(loop, [&] { return received != 0; }));
  EXPECT_EQ(received, GetParam());
  (*watch)->Close();
  EXPECT_EQ((*watch)->state(), HandleState::kClosing);
  watch->reset();
  ExpectClosesClean(loop);
}

INSTANTIATE_TEST_SUITE_P(TermAndInt, SignalTest, ::testing::Values(SIGTERM, SIGINT));

TEST(SignalWatchTest, InvalidSignalNumberIsAnError) {
  EventLoop loop;
  Result<std::unique_ptr<Signal>> watch = Signal::Watch(loop, 100000, [](int) {});
  ASSERT_FALSE(watch.ok());
  EXPECT_NE(watch.error().find("100000"), std::string::npos) << watch.error();
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::loop
