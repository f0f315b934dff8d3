// The farm end to end: real radfarmd, radfarm-agent and radfarm processes on loopback. Every job's
// patches.csv must equal `radfarm render`'s for the same job, byte for byte, whatever the number
// of agents and whatever faults happened on the way.
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>

#include "tests/farm/farm_fixture.h"
#include "tests/farm/kept_results.h"

namespace radfarm::testing {
namespace {

int64_t AgentResults(const nlohmann::json& agents, const std::string& name) {
  if (!agents.is_array()) return -1;
  for (const auto& a : agents) {
    if (a["name"] == name) return a["results"].get<int64_t>();
  }
  return -1;
}

TEST_F(FarmTest, ThreeAgentsRenderTheCornellBoxLikeRadfarmRender) {
  StartMaster();
  for (const char* name : {"a1", "a2", "a3"}) StartAgent(name);
  const int64_t id = Submit("cornell-box.toml");
  ASSERT_TRUE(WaitForState(id, "done"));
  const nlohmann::json job = Status(id);
  EXPECT_EQ(job["stop_reason"], "converged");
  EXPECT_EQ(job["progress"], 1.0);
  const std::string patches = FetchPatches(id);
  ASSERT_FALSE(patches.empty());
  EXPECT_TRUE(patches == ReferencePatches("cornell-box.toml")) << "farm and render differ";
  // Every agent took part.
  const std::string log = MasterLog();
  for (const char* name : {"a1@", "a2@", "a3@"}) {
    EXPECT_GE(CountLines(log, std::string(name)), 1u) << name;
  }
  for (const char* f : {"image.png", "image.exr", "radiosity.ply", "lit.glb", "stats.json"}) {
    EXPECT_TRUE(std::filesystem::exists(Path("fetch-" + std::to_string(id)) + "/" + f)) << f;
  }
}

// A glTF scene lit by KHR_lights_punctual lamps alone: the lamps travel in the job bundle to the
// master, whose solve starts from their light as render's does, to the byte.
TEST_F(FarmTest, ALampLitGltfSceneRendersLikeRadfarmRender) {
  StartMaster();
  StartAgent("a1");
  StartAgent("a2");
  const std::vector<std::string> flags = {"--rays", "2000000", "--patch-size", "0.05"};
  const int64_t id = Submit("cornell-box-lamp.toml", flags);
  ASSERT_TRUE(WaitForState(id, "done")) << MasterLog();
  const std::string patches = FetchPatches(id);
  ASSERT_FALSE(patches.empty());
  EXPECT_TRUE(patches == ReferencePatches("cornell-box-lamp.toml", flags))
      << "farm and render differ";
}

// A ray budget far below what the rounds take at full strength paces them (core/solve_control.h
// PacedRoundCap: 11 rounds instead of one on the Cornell box at 600,000 rays): the master plans
// them from the same state as render, so the agents' job gives render's patches to the byte.
TEST_F(FarmTest, PacedRoundsOfARayBudgetGiveRendersPatches) {
  StartMaster({"--local-round-rays", "0"});
  StartAgent("a1");
  StartAgent("a2");
  const std::vector<std::string> flags = {"--rays", "600000"};
  const int64_t id = Submit("cornell-box.toml", flags);
  ASSERT_TRUE(WaitForState(id, "done")) << MasterLog();
  const nlohmann::json done = Status(id);
  EXPECT_GT(JobRound(done), 3) << done.dump();
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", flags))
      << "farm and render differ";
}

// Rounds of at most --local-round-rays rays are computed by the master itself: with the limit
// above every round of the job, it is solved with no agent at all, and gives render's patches.
TEST_F(FarmTest, RoundsUnderTheLocalLimitAreSolvedByTheMasterAlone) {
  StartMaster({"--local-round-rays", "100000000"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
}

// The final gather's batches depend on the scene alone, so agents idle at the ends of and between
// the shooting rounds compute them ahead (daemon/jobs/gather_ahead.h); the gather round starts with
// those done. The patches are render's to the byte, with it and without it (--gather-ahead-rays 0).
const std::regex& AdoptedLine() {
  static const std::regex line(R"(\(the final gather\): (\d+) of (\d+) batches computed ahead)");
  return line;
}

TEST_F(FarmTest, TheFinalGatherComputedAheadGivesRendersPatches) {
  StartMaster();
  StartAgent("a1");
  StartAgent("a2");
  const int64_t id = Submit("cornell-box.toml");
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml")) << "farm and render differ";
  const std::string log = MasterLog();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, AdoptedLine())) << log;
  EXPECT_GE(std::stoul(m[1].str()), 1u);
  EXPECT_LE(std::stoul(m[1].str()), std::stoul(m[2].str()));
}

// The gather round folds its results as they come (in batch order): the gather-ahead leases an
// agent still held when the round began are computed first, not taken back and leased last. They
// were, and the fold then held nearly every result of the round until its end (3,349 of 3,860
// batches with one agent, 36 MB on the master).
TEST_F(FarmTest, TheGatherRoundFoldsItsResultsAsTheyCome) {
  StartMaster();
  StartAgent("a1");
  const int64_t id = Submit("cornell-box.toml");
  ASSERT_TRUE(WaitForState(id, "done"));
  const std::string log = MasterLog();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, AdoptedLine())) << log;
  const unsigned long batches = std::stoul(m[2].str());
  static const std::regex gather_round(
      R"(round \d+: \d+ rays, unshot 0\.0000%.*; at most (\d+) results held for the fold)");
  ASSERT_TRUE(std::regex_search(log, m, gather_round)) << log;
  EXPECT_LT(std::stoul(m[1].str()), batches / 4) << log;
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml")) << "farm and render differ";
}

TEST_F(FarmTest, WithoutTheGatherAheadThePatchesAreTheSame) {
  StartMaster({"--gather-ahead-rays", "0"});
  StartAgent("a1");
  StartAgent("a2");
  const int64_t id = Submit("cornell-box.toml");
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml")) << "farm and render differ";
  std::smatch m;
  const std::string log = MasterLog();
  EXPECT_FALSE(std::regex_search(log, m, AdoptedLine()));
}

// The master meshes a submitted scene to check it; a job that starts at once is prepared with
// that mesh instead of meshing it again (seconds at 10^5-10^6 patches). A job that waits in the
// queue does not hold its mesh and is meshed when it starts. Both give render's patches.
TEST_F(FarmTest, AJobStartedAtOnceKeepsTheMeshItsSubmissionBuiltAndAQueuedOneMeshesAgain) {
  // No agent yet and no round on the master: the first job waits in round 0, the second queues.
  StartMaster({"--max-running-jobs", "1", "--local-round-rays", "0"});
  const int64_t first = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitUntil([&] {
    return MasterLog().find("job " + std::to_string(first) + ": ") != std::string::npos &&
           MasterLog().find(" compressed)") != std::string::npos;
  })) << MasterLog();
  const int64_t second = Submit("cornell-box.toml", kShortJob);
  EXPECT_EQ(Status(second).value("state", ""), "queued");
  StartAgent("a");
  ASSERT_TRUE(WaitForState(first, "done"));
  ASSERT_TRUE(WaitForState(second, "done"));
  const std::string log = MasterLog();
  EXPECT_NE(
      log.find("job " + std::to_string(first) + ": 3852 patches (meshed at submission), scene"),
      std::string::npos)
      << log;
  EXPECT_NE(log.find("job " + std::to_string(second) + ": 3852 patches, scene"), std::string::npos)
      << log;
  const std::string reference = ReferencePatches("cornell-box.toml", kShortJob);
  EXPECT_TRUE(FetchPatches(first) == reference) << "the kept mesh changed the result";
  EXPECT_TRUE(FetchPatches(second) == reference);
}

TEST_F(FarmTest, AnAgentKilledMidRoundChangesNothing) {
  StartMaster();
  StartAgent("steady");
  ChildProcess& victim = StartAgent("victim", {"--slowdown", "3"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "victim") > 0; })) << MasterLog();
  victim.Signal(SIGKILL);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
  EXPECT_GE(CountLines(MasterLog(), "victim@"), 1u);
}

TEST_F(FarmTest, AFrozenAgentLosesItsLeasesAndItsLateWorkIsNotCounted) {
  StartMaster();
  StartAgent("steady");
  ChildProcess& frozen = StartAgent("frozen", {"--slowdown", "2"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "frozen") > 0; })) << MasterLog();
  const int64_t round_at_freeze = JobRound(Status(id));
  frozen.Signal(SIGSTOP);
  // Past the 2 s timeout its leases go back to the queue and others finish its round.
  ASSERT_TRUE(WaitUntil([&] {
    return CountLines(MasterLog(), "frozen@") > 0 &&
           CountLines(MasterLog(), "missed its heartbeats") > 0;
  })) << MasterLog();
  ASSERT_TRUE(WaitUntil([&] {
    const nlohmann::json job = Status(id);
    return JobRound(job) > round_at_freeze || job["state"] == "done";
  })) << MasterLog();
  frozen.Signal(SIGCONT);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
}

TEST_F(FarmTest, AnAgentWithAWrongSecretIsRefusedAndTheJobGoesOn) {
  StartMaster();
  const std::string wrong = Path("wrong-secret");
  { std::ofstream(wrong) << std::string(64, 'a') << "\n"; }
  std::filesystem::permissions(wrong, std::filesystem::perms::owner_read);
  StartAgent("intruder", {}, wrong);
  StartAgent("good");
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitUntil([&] { return CountLines(MasterLog(), ": refused: ") > 0; })) << MasterLog();
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
  const nlohmann::json agents = Agents();
  EXPECT_EQ(AgentLeases(agents, "intruder"), -1) << agents.dump();  // never listed
  EXPECT_EQ(CountLines(MasterLog(), "intruder@"), 0u);
}

TEST_F(FarmTest, AnAgentJoiningMidJobGetsWork) {
  StartMaster();
  StartAgent("first", {"--slowdown", "3"});
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitUntil([&] { return JobRound(Status(id)) >= 1; })) << MasterLog();
  StartAgent("latecomer");
  ASSERT_TRUE(WaitUntil([&] {
    return AgentResults(Agents(), "latecomer") > 0 || Status(id)["state"] == "done";
  })) << MasterLog();
  EXPECT_GT(CountLines(MasterLog(), "latecomer@"), 0u);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
}

TEST_F(FarmTest, FiftyAgentsConnectAtOnce) {
  StartMaster();
  for (int i = 0; i < 50; ++i) StartAgent("swarm-" + std::to_string(i));
  ASSERT_TRUE(WaitUntil([&] {
    const nlohmann::json agents = Agents();
    return agents.is_array() && agents.size() == 50;
  })) << MasterLog();
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
}

// The job store's promise: SIGKILL the master at any instant, restart it, and every job ends as
// if nothing happened; nothing submitted is lost.
TEST_F(FarmTest, TheMasterKilledAtRandomPointsResumesEveryJobIdentically) {
  const unsigned seed = std::random_device{}();
  std::printf("kill points seed %u\n", seed);
  std::mt19937 random(seed);
  StartMaster();
  const std::string listen =
      "127.0.0.1:" + master_address().substr(master_address().rfind(':') + 1);
  StartAgent("k1");
  StartAgent("k2");
  const int64_t long_job = Submit("cornell-box.toml");
  std::vector<int64_t> short_jobs;
  constexpr int kKills = 20;
  for (int kill = 0; kill < kKills; ++kill) {
    if (kill % 5 == 2) short_jobs.push_back(Submit("cornell-box.toml", kShortJob));
    // A random instant of the job's life: half the kills wait for the job to finish another round
    // first (so it resumes from a later checkpoint each time), then a random delay.
    if (std::bernoulli_distribution(0.5)(random)) {
      const int64_t before = JobRound(Status(long_job));
      std::printf("kill %d: waiting for the round after %lld\n", kill + 1,
                  static_cast<long long>(before));
      WaitUntil([&] {
        const nlohmann::json job = Status(long_job);
        return JobRound(job) > before || job["state"] == "done";
      });
    }
    std::uniform_int_distribution<int> delay_ms(0, 600);
    const int delay = delay_ms(random);
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(delay);
    WaitUntil([&] { return std::chrono::steady_clock::now() >= until; },
              std::chrono::milliseconds(delay + 1000));
    master().Signal(SIGKILL);
    ASSERT_TRUE(master().WaitExit(std::chrono::seconds(30)).has_value());
    std::printf("kill %d: %d ms after the wait\n", kill + 1, delay);
    StartMaster({"--listen", listen});
    ASSERT_TRUE(master().running());
  }
  ASSERT_TRUE(WaitForState(long_job, "done"));
  // The kills landed at different stages: some after checkpoints (the job resumed from one).
  EXPECT_GE(CountLines(MasterLog(), "resuming after round"), 1u) << MasterLog();
  EXPECT_EQ(CountLines(MasterLog(), "listening for agents"), size_t(kKills + 1));
  EXPECT_TRUE(FetchPatches(long_job) == ReferencePatches("cornell-box.toml")) << "seed " << seed;
  // Kills mid-round resumed from the results the store kept (not every kill lands mid-round);
  // the last checkpoint took them with it, so the store does not grow.
  std::printf("restarts that restored batches: %zu\n",
              CountLines(MasterLog(), "batches restored from the store"));
  // Pruned after the job is done (JobRounds::FinishJob), so perhaps just after.
  EXPECT_TRUE(WaitUntil([&] { return KeptResults(Path("master/radfarm.db"), long_job) == 0; }));
  for (int64_t id : short_jobs) {
    ASSERT_TRUE(WaitForState(id, "done"));
    EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob))
        << "job " << id << " seed " << seed;
  }
  const CommandResult list = Cli({"list", "--json"});
  ASSERT_EQ(list.exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(list.out).size(), 1 + short_jobs.size());
}

}  // namespace
}  // namespace radfarm::testing

namespace radfarm::testing {
namespace {

// Datagrams from sd_notify, read from a socket the test binds as NOTIFY_SOCKET.
class NotifySocket {
 public:
  explicit NotifySocket(const std::string& path) : path_(path) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::snprintf(address.sun_path, sizeof address.sun_path, "%s", path.c_str());
    bound_ = ::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  }
  ~NotifySocket() { ::close(fd_); }
  bool bound() const { return bound_; }
  // Everything received so far, datagrams separated by newlines.
  const std::string& Read() {
    char buffer[4096];
    while (true) {
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, MSG_DONTWAIT);
      if (n <= 0) break;
      received_.append(buffer, size_t(n));
      received_ += '\n';
    }
    return received_;
  }

 private:
  std::string path_;
  int fd_ = -1;
  bool bound_ = false;
  std::string received_;
};

TEST_F(FarmTest, TheMasterTellsSystemdWhenItIsReadyAndWhenItStops) {
  NotifySocket notify(Path("notify.sock"));
  ASSERT_TRUE(notify.bound());
  ::setenv("NOTIFY_SOCKET", Path("notify.sock").c_str(), 1);
  StartMaster();
  ::unsetenv("NOTIFY_SOCKET");
  StartAgent("a1");
  ASSERT_TRUE(WaitUntil([&] {
    const std::string& text = notify.Read();
    return text.find("READY=1") != std::string::npos &&
           text.find("; 1 agents") != std::string::npos;
  })) << notify.Read();
  master().Signal(SIGTERM);
  EXPECT_EQ(master().WaitExit(std::chrono::seconds(30)), 0) << MasterLog();
  EXPECT_NE(notify.Read().find("STOPPING=1"), std::string::npos) << notify.Read();
}

}  // namespace
}  // namespace radfarm::testing
