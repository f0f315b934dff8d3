// The agents' port against strangers: connections that never authenticate
// must neither keep a real agent out nor make the master hold memory. Before the fix a 16 MiB
// frame limit applied before the handshake (128 such connections took radfarmd to 1.48 GB) and
// unauthenticated sockets counted toward --max-agents (with 64 slots a real agent waited 20 s).
#include <unistd.h>

#include "tests/farm/farm_fixture.h"
#include "tests/farm/raw_peer.h"

namespace radfarm::testing {
namespace {

constexpr int kJunkConnections = 128;
constexpr int kQuota = 16;

// The `agents` request's "connections" object (door counters), null on failure.
nlohmann::json DoorCountersOf(const std::string& control) {
  const int fd = ConnectUnixSocket(control);
  if (fd < 0) return nullptr;
  (void)SendSome(fd, Frame(R"({"command":"agents"})"));
  const std::optional<std::string> answer = ReadFramePayload(fd, std::chrono::seconds(60));
  ::close(fd);
  if (!answer) return nullptr;
  const nlohmann::json json = nlohmann::json::parse(*answer, nullptr, false);
  return json.is_object() && json.contains("connections") ? json["connections"] : nullptr;
}

uint64_t DoorCounter(const nlohmann::json& counters, const char* key) {
  return counters.is_object() ? counters.value(key, uint64_t{0}) : 0;
}

TEST_F(FarmTest, JunkConnectionsNeitherKeepARealAgentOutNorHoldMemory) {
  StartMaster({"--max-agents", "1", "--max-unauthenticated", std::to_string(kQuota)});
  // Strangers that announce a 16 MiB frame and start sending it are closed from the prefix: the
  // limit before the handshake is 512 bytes, so nothing of the 16 MiB is buffered.
  const std::string big_prefix = FramePrefix(16u << 20) + std::string(64 << 10, 'j');
  constexpr int kOversized = 8;
  for (int i = 0; i < kOversized; ++i) {
    const int fd = ConnectTcpSocket(master_address());
    ASSERT_GE(fd, 0) << i;
    (void)SendSome(fd, big_prefix);
    EXPECT_TRUE(WaitForPeerClose(fd, std::chrono::seconds(60)));
    ::close(fd);
  }
  ASSERT_TRUE(WaitUntil([&] {
    return CountLines(MasterLog(), "frame of 16777216 bytes exceeds the limit of 512 bytes") ==
           size_t{kOversized};
  })) << MasterLog();
  // Then a flood: half send junk, half connect and say nothing. The master accepts them faster
  // than it reads them, so most go for the quota before they say anything.
  std::vector<int> junk;
  for (int i = 0; i < kJunkConnections; ++i) {
    const int fd = ConnectTcpSocket(master_address());
    ASSERT_GE(fd, 0) << i;
    if (i % 2 == 0) (void)SendSome(fd, big_prefix);
    junk.push_back(fd);
  }
  ASSERT_TRUE(WaitUntil([&] {
    return DoorCounter(DoorCountersOf(control()), "accepted") >=
           uint64_t{kJunkConnections + kOversized};
  })) << MasterLog();

  // A real agent gets in at once, although --max-agents is 1 and 16 strangers wait.
  StartAgent("real");
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "real") >= 0; })) << MasterLog();
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));

  // The strangers never held more than the quota, and every one of them went: evicted, at the
  // frame limit or at the handshake deadline.
  ASSERT_TRUE(WaitUntil([&] {
    const nlohmann::json c = DoorCountersOf(control());
    return DoorCounter(c, "evicted") + DoorCounter(c, "closed_before_auth") >=
           uint64_t{kJunkConnections + kOversized};
  })) << MasterLog();
  const nlohmann::json counters = DoorCountersOf(control());
  EXPECT_LE(DoorCounter(counters, "unauthenticated_peak"), uint64_t{kQuota}) << counters;
  EXPECT_EQ(DoorCounter(counters, "unauthenticated"), 0u) << counters;
  EXPECT_GE(DoorCounter(counters, "authenticated"), 1u) << counters;
  const std::string log = MasterLog();

  // Every refused or pre-authentication close is logged, but at most 20 lines per 10 s: the rest
  // are counted in a summary line.
  EXPECT_LT(CountLines(log, ": closed before authentication: "), size_t{kJunkConnections}) << log;
  EXPECT_TRUE(WaitUntil([&] { return CountLines(MasterLog(), "were not logged") > 0; }))
      << MasterLog();

  // A second real agent is refused after its handshake: --max-agents counts agents, not sockets.
  StartAgent("second");
  EXPECT_TRUE(WaitUntil([&] {
    return CountLines(MasterLog(), "refused: the master has its 1 agents (--max-agents)") > 0;
  })) << MasterLog();
  for (int fd : junk) ::close(fd);
}

}  // namespace
}  // namespace radfarm::testing
