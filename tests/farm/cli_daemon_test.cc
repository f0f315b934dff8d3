// The `radfarm` job-queue commands against a real radfarmd: every command, its --json output (the
// keys docs/CONTROL.md documents), and its exit codes (0 ok, 1 failure, 2 bad input or no such
// job, 3 master unreachable).
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "testing/outward_cube.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

nlohmann::json Json(const CommandResult& r) {
  nlohmann::json json = nlohmann::json::parse(r.out, nullptr, false);
  EXPECT_FALSE(json.is_discarded()) << r.out << r.err;
  return json;
}

void ExpectJobKeys(const nlohmann::json& job) {
  for (const char* key : {"id",
                          "name",
                          "state",
                          "priority",
                          "seed",
                          "scene_hash",
                          "patches",
                          "submitted_at_ms",
                          "started_at_ms",
                          "finished_at_ms",
                          "error",
                          "round",
                          "rays",
                          "unshot_fraction",
                          "tolerance",
                          "progress",
                          "rays_per_second",
                          "agents",
                          "eta_seconds",
                          "stop_reason",
                          "waiting_for_agents",
                          "phase",
                          "last_checkpoint",
                          "direct_start",
                          "display"}) {
    EXPECT_TRUE(job.contains(key)) << key << " missing from " << job.dump();
  }
}

TEST_F(FarmTest, EveryQueueCommandAgainstARunningMaster) {
  StartMaster({"--max-running-jobs", "1"});
  const int64_t alpha =
      Submit("cornell-box.toml", {"--name", "alpha", "--priority", "5", "--rays", "3000000"});
  const int64_t beta = Submit("cornell-box.toml", {"--name", "beta"});
  ASSERT_GT(alpha, 0);
  ASSERT_GT(beta, alpha);

  // list: both jobs, documented keys; beta waits behind alpha (one job at a time).
  CommandResult r = Cli({"list", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json jobs = Json(r);
  ASSERT_EQ(jobs.size(), 2u);
  for (const auto& job : jobs) ExpectJobKeys(job);
  EXPECT_EQ(jobs[0]["name"], "alpha");
  EXPECT_EQ(jobs[0]["priority"], 5);
  EXPECT_EQ(jobs[1]["state"], "queued");
  EXPECT_TRUE(jobs[1]["phase"].is_null()) << jobs[1].dump();  // not this master's to run yet
  EXPECT_TRUE(jobs[1]["last_checkpoint"].is_null()) << jobs[1].dump();
  r = Cli({"list"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("beta"), std::string::npos) << r.out;

  // No checkpoint yet: fetch is refused with exit 1.
  r = Cli({"fetch", std::to_string(alpha), "--out", Path("early")});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;

  // pause / resume / cancel, and the state errors (exit 1).
  r = Cli({"pause", std::to_string(beta), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json(r)["state"], "paused");
  r = Cli({"pause", std::to_string(beta)});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  r = Cli({"resume", std::to_string(beta), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json(r)["state"], "queued");
  r = Cli({"cancel", std::to_string(beta), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json(r)["state"], "cancelled");
  r = Cli({"cancel", std::to_string(beta)});
  EXPECT_EQ(r.exit_code, 1);
  r = Cli({"resume", std::to_string(beta)});
  EXPECT_EQ(r.exit_code, 1);

  // No such job: exit 2.
  for (const char* command : {"status", "cancel", "pause", "resume", "log"}) {
    r = Cli({command, "999"});
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.out << r.err;
  }

  // agents: none, then one.
  r = Cli({"agents", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(Json(r).empty());
  StartAgent("worker");
  ASSERT_TRUE(WaitUntil([&] {
    const nlohmann::json agents = Agents();
    return agents.is_array() && agents.size() == 1;
  }));
  const nlohmann::json agent = Agents()[0];
  for (const char* key : {"id", "name", "address", "threads", "rays_per_second", "load", "leases",
                          "connected_ms", "last_heartbeat_ms_ago", "results"}) {
    EXPECT_TRUE(agent.contains(key)) << key << " missing from " << agent.dump();
  }
  EXPECT_EQ(agent["name"], "worker");
  EXPECT_EQ(agent["threads"], 1);

  // status --watch returns once the job ends; then fetch gives render's bytes.
  r = Cli({"status", std::to_string(alpha), "--watch"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json done = Status(alpha);
  ExpectJobKeys(done);
  EXPECT_EQ(done["state"], "done");
  EXPECT_EQ(done["stop_reason"], "ray budget");
  // What the scene's size got, kept after the job is done (core/solve_rules.h): a bigger scene
  // lost its direct-light start and its display without a word.
  EXPECT_EQ(done["direct_start"].get<std::string>().rfind("from the direct light of ", 0), 0u)
      << done.dump();
  EXPECT_EQ(done["display"].get<std::string>().rfind("at its own points: ", 0), 0u) << done.dump();
  r = Cli({"status", std::to_string(alpha)});
  EXPECT_NE(r.out.find("\ndirect light:  from the direct light of "), std::string::npos) << r.out;
  // What its last checkpoint cost, kept after the job ended (a stopping round always writes one).
  EXPECT_TRUE(done["phase"].is_null()) << done.dump();
  const nlohmann::json& checkpoint = done["last_checkpoint"];
  ASSERT_TRUE(checkpoint.is_object()) << done.dump();
  // Rounds are counted from 1 in both: the stopping round is the one checkpointed.
  EXPECT_EQ(checkpoint["round"].get<uint64_t>(), done["round"].get<uint64_t>()) << done.dump();
  EXPECT_GT(checkpoint["bytes"].get<uint64_t>(), done["patches"].get<uint64_t>() * 48)
      << done.dump();
  EXPECT_GE(checkpoint["committed"].get<uint64_t>(), 1u) << done.dump();
  for (const char* ms : {"copy_ms", "encode_ms", "commit_ms", "queued_ms"}) {
    EXPECT_GE(checkpoint[ms].get<double>(), 0.0) << ms << " in " << done.dump();
  }
  // The rounds' rays: a quarter of the 3M budget is kept for the display (core/display_budget.h)
  // and the direct light the master started from spent at most another (core/direct_light.h,
  // StartRayAllowance).
  EXPECT_LE(done["rays"], 3000000 - 3000000 / 4);
  EXPECT_GE(done["rays"], 3000000 - 2 * (3000000 / 4));
  EXPECT_TRUE(FetchPatches(alpha) == ReferencePatches("cornell-box.toml", kShortJob));

  // log: the job's events and the farm-wide ones.
  r = Cli({"log", std::to_string(alpha), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json events = Json(r);
  ASSERT_FALSE(events.empty());
  EXPECT_NE(events.dump().find("submitted"), std::string::npos) << events.dump();
  EXPECT_NE(events.dump().find("done: ray budget"), std::string::npos) << events.dump();
  for (const auto& e : events) {
    EXPECT_TRUE(e.contains("time_ms") && e.contains("level") && e.contains("text")) << e.dump();
  }
  // Without an id: every job's events with the farm's own, each naming its job (it printed
  // nothing after jobs had run, the farm having no event of its own yet).
  r = Cli({"log"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("job " + std::to_string(alpha) + ": done: ray budget"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("job " + std::to_string(alpha) + ": direct light: "), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("job " + std::to_string(alpha) + ": display: "), std::string::npos) << r.out;

  // A bad scene is refused before the master is asked (exit 2), and the master stays up.
  r = Cli({"submit", Path("missing.obj")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.obj"), std::string::npos) << r.err;

  // The master gone: exit 3, naming the socket.
  master().Signal(SIGKILL);
  master().WaitExit(std::chrono::seconds(30));
  r = Cli({"list"});
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find(control()), std::string::npos) << r.err;
}

// Sends `payload` as one frame on the control socket and returns what the master answers before
// it closes the connection.
std::string RawControlExchange(const std::string& socket_path, const std::string& payload) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::snprintf(address.sun_path, sizeof address.sun_path, "%s", socket_path.c_str());
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return "";
  }
  const uint32_t n = static_cast<uint32_t>(payload.size());
  const unsigned char prefix[4] = {uint8_t(n), uint8_t(n >> 8), uint8_t(n >> 16), uint8_t(n >> 24)};
  (void)!::write(fd, prefix, 4);
  (void)!::write(fd, payload.data(), payload.size());
  timeval timeout{30, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::string answer;
  char buffer[4096];
  ssize_t got;
  while ((got = ::read(fd, buffer, sizeof buffer)) > 0) answer.append(buffer, size_t(got));
  ::close(fd);
  return answer;
}

// `status` said "0 agents, ETA ?" forever with no hint that no agent was connected.
TEST_F(FarmTest, StatusSaysWhenTheJobWaitsForAnAgentAndStopsSayingItWhenOneComes) {
  StartMaster();
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_GT(id, 0);
  ASSERT_TRUE(WaitUntil([&] { return Status(id).value("waiting_for_agents", false); }))
      << Status(id).dump() << MasterLog();
  const CommandResult text = Cli({"status", std::to_string(id)});
  EXPECT_NE(text.out.find("no agent connected: start radfarm-agent"), std::string::npos)
      << text.out;
  StartAgent("late");
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_FALSE(Status(id).value("waiting_for_agents", true));
  EXPECT_EQ(Cli({"status", std::to_string(id)}).out.find("no agent connected"), std::string::npos);
}

// submit checks a scene without meshing it; the warnings that need the patches come from the
// master, which meshes it, and submit prints them as render does.
TEST_F(FarmTest, SubmitPrintsTheMastersWarningsAboutThePatches) {
  StartMaster();
  std::ofstream(Path("room.mtl"))
      << "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n";
  std::ofstream(Path("room.obj")) << OutwardCube("wall", true);
  const CommandResult r = Cli({"submit", Path("room.obj"), "--patch-size", "0.1"});
  ASSERT_EQ(r.exit_code, 0) << r.err << MasterLog();
  EXPECT_NE(r.err.find("room.obj: warning: material 'wall' is lit from behind: 100% of the "
                       "emitters' light"),
            std::string::npos)
      << r.err;
  const CommandResult rendered = RunCommand(
      {RADFARM_CLI_PATH, "render", Path("room.obj"), "--patch-size", "0.1", "--out", Path("out")});
  ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
  EXPECT_EQ(r.err, rendered.err) << "submit and render warn alike";
  const CommandResult quiet = Cli({"submit", RADFARM_SOURCE_DIR "/scenes/cornell-box.toml"});
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
}

TEST_F(FarmTest, AMalformedControlRequestCostsOnlyItsConnection) {
  StartMaster();
  const std::string answer = RawControlExchange(control(), "this is not JSON");
  EXPECT_NE(answer.find("bad_request"), std::string::npos) << answer;
  EXPECT_EQ(Cli({"list", "--json"}).exit_code, 0) << MasterLog();
  EXPECT_TRUE(master().WaitExit(std::chrono::milliseconds(0)) == std::nullopt);
  EXPECT_GE(CountLines(MasterLog(), "not valid JSON"), 1u) << MasterLog();
}

}  // namespace
}  // namespace radfarm::testing

namespace radfarm::testing {
namespace {

TEST_F(FarmTest, AHigherPriorityJobGetsTheAgentsFirst) {
  // Every round on the agent: the master traces small rounds itself, beside the agent, and the
  // low job could end its last rounds there first on a slow build (the likeliest reason this
  // test failed once under ASan).
  StartMaster({"--local-round-rays", "0"});
  StartAgent("only", {"--slowdown", "2"});
  const int64_t low = Submit("cornell-box.toml", {"--rays", "3000000", "--name", "low"});
  ASSERT_TRUE(WaitUntil([&] { return Status(low)["state"] == "running"; }));
  const int64_t high =
      Submit("cornell-box.toml", {"--rays", "3000000", "--name", "high", "--priority", "9"});
  ASSERT_TRUE(WaitForState(high, "done"));
  ASSERT_TRUE(WaitForState(low, "done"));
  const nlohmann::json h = Status(high), l = Status(low);
  EXPECT_LT(h["finished_at_ms"].get<int64_t>(), l["finished_at_ms"].get<int64_t>())
      << h.dump() << "\n"
      << l.dump();
  // Both still match render, whatever the interleaving.
  EXPECT_TRUE(FetchPatches(high) == ReferencePatches("cornell-box.toml", {"--rays", "3000000"}));
  EXPECT_TRUE(FetchPatches(low) == ReferencePatches("cornell-box.toml", {"--rays", "3000000"}));
}

}  // namespace
}  // namespace radfarm::testing
