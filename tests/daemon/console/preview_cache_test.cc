// PreviewCache: previews drawn once per checkpoint, shared by concurrent requests, and dropped
// when every requester has gone. Before it, each request read the whole solution and meshed the
// scene again: 64 clients of a 128k-patch job held a core, and what they abandoned kept a core
// busy for 3 minutes after they left.
#include "daemon/console/preview_cache.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <thread>
#include <vector>

namespace radfarm::daemon {
namespace {

constexpr std::chrono::seconds kLong{60};  // a bound no passing test reaches

TEST(PreviewCacheTest, ConcurrentRequestsForOneCheckpointShareOneComputation) {
  PreviewCache cache;
  const PreviewKey key{7, 12, 1000};
  std::vector<PreviewCache::Joined> requests;
  for (int i = 0; i < 64; ++i) requests.push_back(cache.Join(key));
  EXPECT_TRUE(requests[0].compute);
  for (int i = 1; i < 64; ++i) {
    EXPECT_FALSE(requests[size_t(i)].compute) << i;
    EXPECT_EQ(requests[size_t(i)].flight, requests[0].flight) << i;
  }
  // Waiters on other threads all get the one drawing.
  std::vector<std::thread> waiters;
  std::atomic<int> answered = 0;
  for (int i = 0; i < 8; ++i) {
    waiters.emplace_back([&, flight = requests[size_t(i)].flight] {
      const auto png = flight->Wait(-1, kLong);
      if (png && *png && **png == "png") ++answered;
    });
  }
  cache.Finish(requests[0].flight, std::string("png"));
  for (std::thread& t : waiters) t.join();
  EXPECT_EQ(answered, 8);
  for (const PreviewCache::Joined& r : requests) cache.Leave(r.flight);
  EXPECT_EQ(cache.drawn(), 1u);
  EXPECT_EQ(cache.shared(), 63u);
}

TEST(PreviewCacheTest, APreviewIsKeptForItsCheckpointUntilANewerOneIsAskedFor) {
  PreviewCache cache;
  PreviewCache::Joined first = cache.Join({7, 12, 1000});
  cache.Finish(first.flight, std::string("round 12"));
  cache.Leave(first.flight);
  // Asked again, later: answered at once from the kept flight.
  PreviewCache::Joined again = cache.Join({7, 12, 1000});
  EXPECT_FALSE(again.compute);
  ASSERT_TRUE(again.flight->finished());
  EXPECT_EQ(**again.flight->Wait(-1, kLong), "round 12");
  cache.Leave(again.flight);
  // A newer checkpoint is drawn anew, and the old preview goes.
  PreviewCache::Joined newer = cache.Join({7, 13, 2000});
  EXPECT_TRUE(newer.compute);
  cache.Finish(newer.flight, std::string("round 13"));
  cache.Leave(newer.flight);
  EXPECT_TRUE(cache.Join({7, 12, 1000}).compute);
  // Another job's preview is its own.
  EXPECT_TRUE(cache.Join({8, 12, 1000}).compute);
}

TEST(PreviewCacheTest, AFailedDrawingIsNotKept) {
  PreviewCache cache;
  PreviewCache::Joined joined = cache.Join({7, 12, 1000});
  cache.Finish(joined.flight, Error{"the store failed"});
  EXPECT_FALSE((*joined.flight->Wait(-1, kLong)).ok());
  cache.Leave(joined.flight);
  EXPECT_TRUE(cache.Join({7, 12, 1000}).compute);
}

TEST(PreviewCacheTest, TheLastRequesterLeavingCancelsTheComputation) {
  PreviewCache cache;
  const PreviewKey key{7, 12, 1000};
  PreviewCache::Joined a = cache.Join(key), b = cache.Join(key);
  cache.Leave(a.flight);
  EXPECT_FALSE(a.flight->cancelled());  // b still waits
  cache.Leave(b.flight);
  EXPECT_TRUE(a.flight->cancelled());
  EXPECT_EQ(cache.cancelled(), 1u);
  // The cancelled work ends; what it drew is not kept, and a new request starts afresh.
  cache.Finish(a.flight, Error{"preview cancelled"});
  PreviewCache::Joined c = cache.Join(key);
  EXPECT_TRUE(c.compute);
  EXPECT_NE(c.flight, a.flight);
  EXPECT_FALSE(c.flight->cancelled());
  EXPECT_EQ(cache.drawn(), 0u);
}

TEST(PreviewCacheTest, ClosingEndsEveryWaitAndKeepsNothing) {
  PreviewCache cache;
  PreviewCache::Joined running = cache.Join({7, 12, 1000});
  PreviewCache::Joined drawn = cache.Join({8, 3, 1000});
  cache.Finish(drawn.flight, std::string("png"));
  std::thread waiter([&] {
    const auto png = running.flight->Wait(-1, kLong);
    ASSERT_TRUE(png.has_value());
    EXPECT_EQ(png->error(), "the master is shutting down");
  });
  cache.Close("the master is shutting down");
  waiter.join();
  cache.Finish(running.flight, std::string("too late"));  // ignored
  EXPECT_FALSE((*running.flight->Wait(-1, kLong)).ok());
  EXPECT_TRUE(cache.Join({8, 3, 1000}).compute);
}

TEST(PreviewCacheTest, AWaitEndsWhenItsClientCloses) {
  PreviewCache cache;
  PreviewCache::Joined joined = cache.Join({7, 12, 1000});
  int sockets[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, sockets), 0);
  ::close(sockets[1]);  // the client goes before the preview is drawn
  EXPECT_FALSE(joined.flight->Wait(sockets[0], kLong).has_value());
  ::close(sockets[0]);
  cache.Leave(joined.flight);
  EXPECT_TRUE(joined.flight->cancelled());
}

TEST(PreviewCacheTest, AClientThatStaysIsAnsweredWhenTheDrawingEnds) {
  PreviewCache cache;
  PreviewCache::Joined joined = cache.Join({7, 12, 1000});
  int sockets[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, sockets), 0);
  ASSERT_EQ(::write(sockets[1], "GET", 3), 3);  // a pipelined request is no leave
  std::thread drawer([&] { cache.Finish(joined.flight, std::string("png")); });
  const auto png = joined.flight->Wait(sockets[0], kLong);
  drawer.join();
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(**png, "png");
  ::close(sockets[0]);
  ::close(sockets[1]);
}

}  // namespace
}  // namespace radfarm::daemon
