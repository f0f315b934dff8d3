#include "loop/async.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::ExpectClosesClean;
using testing::RunUntil;

TEST(AsyncTest, SendFromAnotherThreadRunsTheCallbackOnTheLoopThread) {
  EventLoop loop;
  const std::thread::id loop_thread = std::this_thread::get_id();
  std::atomic<int> produced{0};
  int seen = 0;
  bool on_loop_thread = true;
  Result<std::unique_ptr<Async>> async = Async::Create(loop, [&] {
    on_loop_thread = on_loop_thread && std::this_thread::get_id() == loop_thread;
    seen = produced.load();
  });
  ASSERT_TRUE(async.ok()) << async.error();
  std::thread sender([&] {
    for (int i = 0; i < 1000; ++i) {
      produced.fetch_add(1);
      (*async)->Send();
    }
  });
  ASSERT_TRUE(RunUntil(loop, [&] { return seen == 1000; }));
  sender.join();  // every sender stops before the Async closes
  EXPECT_TRUE(on_loop_thread);
  async->reset();
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::loop
