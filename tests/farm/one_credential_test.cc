// One agent credential against the master: many connections under one name, and frames trickled
// a few bytes at a time. Before the limits, 60 connections under one enrolled name, each 15 MiB
// into a frame, held 938 MB in radfarmd, and with --max-agents 4 one name took every place.
#include <unistd.h>

#include <memory>
#include <vector>

#include "tests/farm/farm_fixture.h"
#include "tests/farm/raw_agent.h"
#include "tests/farm/raw_peer.h"

namespace radfarm::testing {
namespace {

constexpr std::chrono::seconds kWait{60};  // generous: 2 shared cores

// The `agents` request's "connections" object, null on failure.
nlohmann::json ConnectionCounters(const std::string& control) {
  const int fd = ConnectUnixSocket(control);
  if (fd < 0) return nullptr;
  (void)SendSome(fd, Frame(R"({"command":"agents"})"));
  const std::optional<std::string> answer = ReadFramePayload(fd, kWait);
  ::close(fd);
  if (!answer) return nullptr;
  const nlohmann::json json = nlohmann::json::parse(*answer, nullptr, false);
  return json.is_object() && json.contains("connections") ? json["connections"] : nullptr;
}

uint64_t Counter(const nlohmann::json& counters, const char* key) {
  return counters.is_object() ? counters.value(key, uint64_t{0}) : 0;
}

protocol::FarmSecret FarmSecretOf(const LoopbackFarm& farm) {
  return protocol::FarmSecret::FromHex(farm.secret_hex()).value();
}

TEST_F(FarmTest, OneNameHoldsAtMostItsConnectionsAndAnotherAgentStillGetsIn) {
  StartMaster({"--max-agents", "4"});
  const protocol::FarmSecret secret = FarmSecretOf(farm_);
  constexpr int kConnections = 8;
  std::vector<std::unique_ptr<RawAgent>> one_name;
  for (int i = 0; i < kConnections; ++i) {
    one_name.push_back(std::make_unique<RawAgent>(master_address(), secret, "one-key"));
    ASSERT_TRUE(one_name.back()->welcomed()) << i << "\n" << MasterLog();
  }
  // The first two stay (--max-connections-per-agent 2); each later one is refused right after
  // its Welcome, told why.
  for (int i = 2; i < kConnections; ++i) {
    const std::optional<std::string> refusal = one_name[size_t(i)]->ReadClose(kWait);
    ASSERT_TRUE(refusal.has_value()) << i << "\n" << MasterLog();
    EXPECT_EQ(*refusal, "agent one-key already has 2 connections (--max-connections-per-agent)");
  }
  EXPECT_EQ(Counter(ConnectionCounters(control()), "refused_per_agent"),
            uint64_t{kConnections - 2});

  // Another agent takes one of the places left and computes a job.
  StartAgent("real");
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "real") >= 0; })) << MasterLog();
  one_name.clear();  // their leases go back at once, not after agent_timeout_ms
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
}

TEST_F(FarmTest, FramesTrickledByManyAgentsHoldAtMostTheMastersBudget) {
  constexpr uint64_t kBudget = uint64_t{32} << 20;
  StartMaster({"--max-frame-bytes-held", std::to_string(kBudget)});
  const protocol::FarmSecret secret = FarmSecretOf(farm_);
  // Six names, each 8 MiB into a frame of 15 MiB that never ends: 48 MiB announced and sent,
  // more than the budget holds.
  const std::string partial = FramePrefix(15u << 20) + std::string(8u << 20, 't');
  constexpr int kTricklers = 6;
  std::vector<std::unique_ptr<RawAgent>> tricklers;
  for (int i = 0; i < kTricklers; ++i) {
    tricklers.push_back(
        std::make_unique<RawAgent>(master_address(), secret, "trickle-" + std::to_string(i)));
    ASSERT_TRUE(tricklers.back()->welcomed()) << i << "\n" << MasterLog();
    (void)tricklers.back()->SendAll(partial);  // false once the master closed it
  }
  // Every byte sent is held or refused: then the master has seen them all.
  ASSERT_TRUE(WaitUntil([&] {
    const nlohmann::json c = ConnectionCounters(control());
    return Counter(c, "frames_refused_over_budget") >= 2;
  })) << MasterLog();
  const nlohmann::json counters = ConnectionCounters(control());
  EXPECT_LE(Counter(counters, "frame_bytes_held_peak"), kBudget) << counters;
  EXPECT_LE(Counter(counters, "frame_bytes_held"), kBudget) << counters;
  EXPECT_EQ(Counter(counters, "max_frame_bytes_held"), kBudget) << counters;
  EXPECT_GE(CountLines(MasterLog(), "unfinished frames already hold"), 2u) << MasterLog();

  // Gone, they hold nothing.
  tricklers.clear();
  EXPECT_TRUE(WaitUntil([&] {
    return Counter(ConnectionCounters(control()), "frame_bytes_held") == 0;
  })) << ConnectionCounters(control());
}

// Hostile neighbours: one agent holding the whole budget in a frame that never ends made every
// other agent's next buffered frame fail. Now the connection holding the most is the one closed,
// and the other's frame goes on to its own checks (junk here: it fails authentication).
TEST_F(FarmTest, AnAgentHoldingTheFrameBudgetIsClosedNotTheOneSendingAfterIt) {
  constexpr uint64_t kBudget = uint64_t{16} << 20;  // the least allowed: one whole frame
  StartMaster({"--max-frame-bytes-held", std::to_string(kBudget)});
  const protocol::FarmSecret secret = FarmSecretOf(farm_);
  RawAgent hog(master_address(), secret, "hog");
  RawAgent other(master_address(), secret, "other");
  ASSERT_TRUE(hog.welcomed() && other.welcomed()) << MasterLog();
  // A frame of the whole budget, all but its last byte: its buffer holds every byte allowed.
  ASSERT_TRUE(hog.SendAll(FramePrefix(uint32_t{kBudget}) + std::string(kBudget - 1, 'h')));
  ASSERT_TRUE(WaitUntil([&] {
    return Counter(ConnectionCounters(control()), "frame_bytes_held") == kBudget;
  })) << ConnectionCounters(control());

  (void)other.SendAll(FramePrefix(1u << 20) + std::string(1u << 20, 'o'));
  ASSERT_TRUE(hog.WaitForClose(kWait)) << MasterLog();
  ASSERT_TRUE(other.WaitForClose(kWait)) << MasterLog();
  const nlohmann::json counters = ConnectionCounters(control());
  EXPECT_EQ(Counter(counters, "frames_evicted_over_budget"), 1u) << counters;
  EXPECT_EQ(Counter(counters, "frames_refused_over_budget"), 1u) << counters;
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "hog@", "closed holding the most bytes"), 1u)
      << MasterLog();
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "other@", "unfinished frames already hold"), 0u)
      << MasterLog();
  EXPECT_TRUE(WaitUntil([&] {
    return Counter(ConnectionCounters(control()), "frame_bytes_held") == 0;
  })) << ConnectionCounters(control());
}

}  // namespace
}  // namespace radfarm::testing
