// The real radfarm-agent under its idle policy, against the fake master: a simulated user (the
// --idle-source file) who comes back mid-job gets every lease handed back and no result sent; the
// agent takes work again once the user is idle again. A synthetic CPU load (busy child processes)
// keeps it from taking work. And systemd's notifications: READY=1, STATUS=, STOPPING=1.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <thread>

#include "codec/patch_scene_codec.h"
#include "protocol/batch_convert.h"
#include "protocol/scene_transfer.h"
#include "tests/agent/agent_process.h"
#include "tests/agent/fake_master.h"
#include "tests/agent/test_farm.h"
#include "tests/loop/loop_test_util.h"

extern char** environ;

namespace radfarm::agent::testing {
namespace {

// The policy the tests run: the user file alone decides (user_idle_minutes = 0: "idle" counts
// at once; max_other_cpu = 1: the load is ignored, this machine's other tests may load it), and
// resuming waits 2 x poll_seconds = 2 s.
constexpr const char* kUserOnlyPolicy =
    "[idle]\n"
    "user_idle_minutes = 0\n"
    "max_other_cpu = 1\n"
    "poll_seconds = 1\n";

size_t Returned(const Record& r) {
  size_t n = 0;
  for (const auto& back : r.All<protocol::LeaseReturnMsg>()) n += back.leases.size();
  return n;
}

class AgentIdleTest : public ::testing::Test {
 protected:
  AgentIdleTest()
      : scene_(BoxScene(3)),
        blob_(codec::EncodePatchScene(scene_)),
        secret_(TestSecret(0x3c)),
        master_(secret_, Heartbeats(250, true)) {
    WriteSecretFile(dir_.File("key"), secret_);
    master_.AddScene(blob_);
  }

  // The simulated user: the file is replaced atomically, as FileUserIdle asks.
  void SetUser(const std::string& word) {
    WriteTextFile(dir_.File("user.tmp"), word + "\n");
    std::filesystem::rename(dir_.File("user.tmp"), dir_.File("user"));
  }

  std::vector<std::string> IdleArgs(const std::string& policy, unsigned threads = 1) {
    WriteTextFile(dir_.File("agent.conf"), policy);
    return AgentArgs(master_.address(), dir_.File("key"), threads,
                     {"--config", dir_.File("agent.conf"), "--idle-source", dir_.File("user")});
  }

  // Waits until `n` connections have been authenticated and one is open.
  bool WaitConnected(int n, const AgentProcess& agent) {
    const bool ok =
        master_.WaitFor([n](const Record& r) { return r.authenticated == n && r.open == 1; });
    EXPECT_TRUE(ok) << agent.Log();
    return ok;
  }

  protocol::AssignedBatch Assign(const TestJob& job, uint64_t batch, uint32_t shooter,
                                 uint64_t first_ray, uint32_t rays) {
    return Assignment(job, blob_, scene_, batch, shooter, first_ray, rays);
  }

  // Sends `assignment` and checks its result equals BatchTracer's on this machine.
  void ExpectWorks(const protocol::AssignedBatch& assignment, const AgentProcess& agent) {
    master_.Send(assignment);
    std::optional<protocol::BatchOutcome> found;
    ASSERT_TRUE(master_.WaitFor([&](const Record& r) {
      for (const auto& result : r.results) {
        if (result.lease == assignment.lease) found = result;
      }
      return found.has_value();
    })) << agent.Log();
    EXPECT_EQ(protocol::ToBatchResult(*found), RunLocally(scene_, assignment));
  }

  ScratchDir dir_;
  PatchScene scene_;
  std::vector<uint8_t> blob_;
  protocol::FarmSecret secret_;
  FakeMaster master_;
};

TEST_F(AgentIdleTest, AReturningUserGetsEveryLeaseBackAndNoResultIsSent) {
  SetUser("idle");
  AgentProcess agent(IdleArgs(kUserOnlyPolicy));
  ASSERT_TRUE(WaitConnected(1, agent));
  // One batch long enough to be running when the user comes back, two queued behind it.
  const auto running = Assign(Job(1), 1, 2, 0, kLongBatchRays);
  const auto queued_a = Assign(Job(1), 2, 3, 0, 1000);
  const auto queued_b = Assign(Job(1), 3, 4, 0, 1000);
  master_.Send({running, queued_a, queued_b});
  ASSERT_TRUE(agent.WaitForLog("ready, ")) << agent.Log();

  SetUser("busy");
  // Every lease comes back, as Overloaded, and the agent closes its connection.
  ASSERT_TRUE(master_.WaitFor([](const Record& r) { return Returned(r) == 3 && r.open == 0; }))
      << agent.Log();
  std::set<std::pair<uint64_t, uint64_t>> returned;
  for (const auto& back : master_.Snapshot().All<protocol::LeaseReturnMsg>()) {
    EXPECT_EQ(back.reason, protocol::LeaseReturnReason::kOverloaded);
    for (const auto& lease : back.leases) returned.insert({lease.job_id, lease.batch_id});
  }
  EXPECT_EQ(returned, (std::set<std::pair<uint64_t, uint64_t>>{{1, 1}, {1, 2}, {1, 3}}));
  EXPECT_TRUE(agent.WaitForLog("not taking work: user active")) << agent.Log();
  EXPECT_TRUE(agent.WaitForLog("pausing: user active; returning 3 leases")) << agent.Log();
  // The running batch finishes on a worker; its result is discarded, not sent.
  ASSERT_TRUE(agent.WaitForLog("discarded the result of a lease no longer held")) << agent.Log();
  EXPECT_TRUE(master_.Snapshot().results.empty()) << agent.Log();
  EXPECT_EQ(master_.Snapshot().authenticated, 1) << agent.Log();  // no reconnection while busy

  // The user leaves: the agent connects again and takes work.
  SetUser("idle");
  ASSERT_TRUE(WaitConnected(2, agent));
  EXPECT_TRUE(agent.WaitForLog("resuming: idle: user idle")) << agent.Log();
  ExpectWorks(Assign(Job(2), 1, 5, 0, 2000), agent);
  for (const auto& result : master_.Snapshot().results) {
    EXPECT_NE(result.lease.job_id, 1u)
        << "a result for a returned lease, batch " << result.lease.batch_id;
  }
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST_F(AgentIdleTest, ABusyUserAtStartKeepsTheAgentAwayUntilIdle) {
  SetUser("busy");
  AgentProcess agent(IdleArgs(kUserOnlyPolicy));
  // The policy's first answer comes before any connection attempt.
  ASSERT_TRUE(agent.WaitForLog("waiting: user active")) << agent.Log();
  EXPECT_EQ(master_.Snapshot().accepted, 0) << agent.Log();
  SetUser("idle");
  ASSERT_TRUE(WaitConnected(1, agent));
  ExpectWorks(Assign(Job(3), 1, 0, 0, 1000), agent);
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST_F(AgentIdleTest, TheMastersLeasesReturnEachTimeTheUserComesBack) {
  SetUser("idle");
  AgentProcess agent(IdleArgs(kUserOnlyPolicy, 2));
  for (int visit = 1; visit <= 2; ++visit) {
    ASSERT_TRUE(WaitConnected(visit, agent));
    const auto a = Assign(Job(10 + visit), 1, 1, 0, kLongBatchRays);
    const auto b = Assign(Job(10 + visit), 2, 2, 0, kLongBatchRays);
    master_.Send({a, b});
    // Both leases are held (the scene is fetched on the first visit only).
    ASSERT_TRUE(agent.WaitForLog("lease job " + std::to_string(10 + visit) + " batch 2 attempt"))
        << agent.Log();
    SetUser("busy");
    ASSERT_TRUE(master_.WaitFor([visit](const Record& r) {
      return Returned(r) == 2 * static_cast<size_t>(visit) && r.open == 0;
    })) << agent.Log();
    SetUser("idle");
  }
  ASSERT_TRUE(WaitConnected(3, agent));
  EXPECT_TRUE(master_.Snapshot().results.empty()) << agent.Log();
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

// Busy child processes, at least four per core, killed by the destructor.
class CpuBurner {
 public:
  CpuBurner() {
    const long cores = std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
    for (long i = 0; i < 4 * cores; ++i) {
      char sh[] = "/bin/sh", c[] = "-c", loop[] = "while :; do :; done";
      char* argv[] = {sh, c, loop, nullptr};
      pid_t pid = -1;
      if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv, environ) == 0) pids_.push_back(pid);
    }
  }
  ~CpuBurner() {
    for (pid_t pid : pids_) kill(pid, SIGKILL);
    for (pid_t pid : pids_) waitpid(pid, nullptr, 0);
  }
  CpuBurner(const CpuBurner&) = delete;
  CpuBurner& operator=(const CpuBurner&) = delete;
  size_t size() const { return pids_.size(); }

 private:
  std::vector<pid_t> pids_;
};

TEST_F(AgentIdleTest, ASyntheticCpuLoadKeepsTheAgentFromTakingWork) {
  if (!std::filesystem::exists("/proc/stat")) GTEST_SKIP() << "no /proc/stat here";
  CpuBurner burner;
  ASSERT_GT(burner.size(), 0u);
  SetUser("idle");
  // Four busy processes a core leave the other processes' share near 100%, far above 50%.
  AgentProcess agent(
      IdleArgs("[idle]\nuser_idle_minutes = 0\nmax_other_cpu = 0.5\n"
               "poll_seconds = 1\n"));
  ASSERT_TRUE(agent.WaitForLog("not taking work: other processes use")) << agent.Log();
  ASSERT_TRUE(agent.WaitForLog("waiting: other processes use")) << agent.Log();
  EXPECT_EQ(master_.Snapshot().accepted, 0) << agent.Log();
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST_F(AgentIdleTest, WithoutAnEnabledIdleTableTheAgentConnectsAtOnce) {
  // No [idle] table: the policy is off; enabled = false: the same.
  for (const char* config : {"threads = 1\n", "[idle]\nenabled = false\n"}) {
    SCOPED_TRACE(config);
    FakeMaster master(secret_, Heartbeats(250, true));
    master.AddScene(blob_);
    WriteTextFile(dir_.File("plain.conf"), config);
    AgentProcess agent(
        AgentArgs(master.address(), dir_.File("key"), 1, {"--config", dir_.File("plain.conf")}));
    ASSERT_TRUE(master.WaitFor([](const Record& r) { return r.authenticated == 1; }))
        << agent.Log();
    EXPECT_EQ(agent.CountInLog("idle policy on"), 0) << agent.Log();
    agent.Signal(SIGTERM);
    EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
  }
}

// A datagram socket standing in for systemd's NOTIFY_SOCKET.
class NotifySocket {
 public:
  explicit NotifySocket(const std::string& path) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::snprintf(address.sun_path, sizeof address.sun_path, "%s", path.c_str());
    bound_ = fd_ >= 0 && ::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  }
  ~NotifySocket() {
    if (fd_ >= 0) ::close(fd_);
  }
  NotifySocket(const NotifySocket&) = delete;
  NotifySocket& operator=(const NotifySocket&) = delete;
  bool bound() const { return bound_; }
  // Everything received so far, one datagram a line.
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
  bool WaitFor(const std::string& text) {
    return loop::testing::WaitFor([&] { return Read().find(text) != std::string::npos; },
                                  kWaitTimeout);
  }

 private:
  int fd_ = -1;
  bool bound_ = false;
  std::string received_;
};

TEST_F(AgentIdleTest, TheAgentTellsSystemdItIsReadyWhatItDoesAndThatItStops) {
  NotifySocket notify(dir_.File("notify.sock"));
  ASSERT_TRUE(notify.bound());
  SetUser("busy");
  ::setenv("NOTIFY_SOCKET", dir_.File("notify.sock").c_str(), 1);
  AgentProcess agent(IdleArgs(kUserOnlyPolicy));
  ::unsetenv("NOTIFY_SOCKET");
  ASSERT_TRUE(notify.WaitFor("READY=1")) << notify.Read() << agent.Log();
  ASSERT_TRUE(notify.WaitFor("STATUS=waiting: user active")) << notify.Read() << agent.Log();
  SetUser("idle");
  ASSERT_TRUE(notify.WaitFor("STATUS=connected to " + master_.address() + ", 0 leases"))
      << notify.Read() << agent.Log();
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
  EXPECT_NE(notify.Read().find("STOPPING=1"), std::string::npos) << notify.Read();
  // READY=1 came once, before any STATUS= of a connection.
  const std::string& text = notify.Read();
  EXPECT_EQ(text.find("READY=1"), text.rfind("READY=1")) << text;
  EXPECT_LT(text.find("READY=1"), text.find("STATUS=connected")) << text;
}

}  // namespace
}  // namespace radfarm::agent::testing
