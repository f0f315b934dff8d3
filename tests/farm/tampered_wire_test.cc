// An attacker on one agent's link flips bits after the handshake (TamperProxy). The sealed frames
// (protocol/frame_seal.h) make the master drop that connection with "frame failed authentication"
// naming the peer; the wire is blamed, not the agent: it reconnects and is never blocklisted, a
// healthy agent on the same host keeps working, and the job still ends with render's bytes.

#include "tests/farm/farm_fixture.h"
#include "tests/farm/tamper_proxy.h"

namespace radfarm::testing {
namespace {

TEST_F(FarmTest, AFrameTamperedOnTheWireDropsOnlyThatConnectionAndBlamesNoAgent) {
  StartMaster();
  TamperProxy proxy(master_address(), /*tampered_connections=*/2);
  ASSERT_FALSE(proxy.address().empty());
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ChildProcess& wired = farm_.StartAgent("wired", 1, {}, "", proxy.address());
  StartAgent("steady", {"--slowdown", "2"});  // same host; slower, so "wired" gets work too
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob))
      << "farm and render differ";

  ASSERT_GE(proxy.flips(), 1) << MasterLog();
  // Every flipped frame ended its connection, with the peer named and the reason given.
  const std::string log = MasterLog();
  EXPECT_GE(CountLinesWithBoth(log, "wired@", "frame failed authentication"), size_t(proxy.flips()))
      << log;
  EXPECT_EQ(CountLinesWithBoth(log, "steady@", "frame failed authentication"), 0u) << log;
  // The agent came back after each, and nothing was held against it or its host.
  ASSERT_TRUE(WaitUntil([&] { return proxy.connections() > proxy.flips(); })) << wired.Log();
  ASSERT_TRUE(WaitUntil([&] {
    return CountLinesWithBoth(MasterLog(), "wired@", " connected (") > size_t(proxy.flips());
  })) << MasterLog();
  EXPECT_EQ(CountLines(MasterLog(), "blocklisted"), 0u) << MasterLog();
  EXPECT_EQ(CountLines(MasterLog(), "result rejected"), 0u) << MasterLog();
  EXPECT_GE(CountLinesWithBoth(log, "steady@", " connected ("), 1u);
  EXPECT_EQ(CountLinesWithBoth(log, "steady@", "disconnected"), 0u) << log;
  // The agent was told why.
  EXPECT_GE(CountLines(wired.Log(), "frame failed authentication"), 1u) << wired.Log();
}

}  // namespace
}  // namespace radfarm::testing
