// radfarmd's web console (--http) against a real farm on loopback: /metrics scraped and checked
// line by line, the status JSON and its event stream, and pause/resume/cancel with and without
// the token. The page itself is driven in a real browser by status_page_browser_test.cc.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "testing/http_client.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

const std::string kToken = "web-token-0123456789abcdef";

class WebConsoleTest : public FarmTest {
 protected:
  // Starts the master with the web console on a free loopback port; returns its HOST:PORT.
  std::string StartMasterWithConsole(bool with_token, std::vector<std::string> flags = {}) {
    flags.insert(flags.end(), {"--http", "127.0.0.1:0"});
    if (with_token) {
      std::ofstream(Path("web.token")) << kToken << "\n";
      flags.insert(flags.end(), {"--http-token-file", Path("web.token")});
    }
    StartMaster(flags);
    const std::string address = ReadFile(farm_.state_dir() + "/http.addr");
    EXPECT_FALSE(address.empty()) << MasterLog();
    return address.substr(0, address.find('\n'));
  }

  HttpResponse Request(const std::string& method, const std::string& path,
                       const std::vector<std::string>& headers = {}) {
    Result<HttpResponse> r = HttpRequest(address_, method, path, headers);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error());
    return r.ok() ? *r : HttpResponse{};
  }

  // /metrics as name{labels} -> value; fails the test on a line outside the format.
  std::map<std::string, double> Scrape() {
    const HttpResponse r = Request("GET", "/metrics");
    EXPECT_EQ(r.status, 200);
    EXPECT_EQ(r.headers.at("content-type"), "text/plain; version=0.0.4; charset=utf-8");
    const std::regex sample(R"(^([a-zA-Z_:][a-zA-Z0-9_:]*(\{[^}]*\})?) (\S+)$)");
    std::map<std::string, double> values;
    std::istringstream lines(r.body);
    std::string line;
    while (std::getline(lines, line)) {
      if (line.rfind("# HELP ", 0) == 0 || line.rfind("# TYPE ", 0) == 0) continue;
      std::smatch m;
      EXPECT_TRUE(std::regex_match(line, m, sample)) << line;
      if (!m.empty()) values[m[1]] = std::stod(m[3]);
    }
    return values;
  }

  std::string address_;
};

TEST_F(WebConsoleTest, MetricsCountARealJobsBatchesCheckpointsAndAgents) {
  // Every round on the agent (none computed by the master), so batches are leased.
  address_ = StartMasterWithConsole(false, {"--local-round-rays", "0"});
  StartAgent("metrics-agent");
  ASSERT_TRUE(farm_.WaitForAgents(1, std::chrono::seconds(60)));
  const int64_t id = Submit("cornell-box.toml", {"--rays", "3000000"});
  ASSERT_TRUE(WaitForState(id, "done"));
  // The page's snapshot follows the store within a refresh: poll until it shows the job done.
  std::map<std::string, double> m;
  ASSERT_TRUE(WaitUntil(
      [&] {
        m = Scrape();
        return m["radfarm_jobs{state=\"done\"}"] == 1;
      },
      std::chrono::seconds(60)));
  EXPECT_EQ(m["radfarm_jobs{state=\"running\"}"], 0);
  EXPECT_EQ(m["radfarm_jobs{state=\"queued\"}"], 0);
  EXPECT_EQ(m["radfarm_agents{state=\"idle\"}"] + m["radfarm_agents{state=\"busy\"}"], 1);
  // The agents' rays: the master's direct light spends up to a quarter of the 3M budget, and a
  // quarter is kept for the display.
  EXPECT_GE(m["radfarm_rays_total"], 3000000 - 2 * (3000000 / 4));
  EXPECT_GT(m["radfarm_batches_issued_total"], 0);
  EXPECT_GT(m["radfarm_batch_results_accepted_total"], 0);
  EXPECT_LE(m["radfarm_batch_results_accepted_total"], m["radfarm_batches_issued_total"]);
  EXPECT_EQ(m["radfarm_batch_results_rejected_total{reason=\"invalid\"}"], 0);
  EXPECT_TRUE(m.count("radfarm_batches_reissued_total{why=\"requeued\"}"));
  // Every round checkpoints by default: at least one commit was timed, all within +Inf.
  const double checkpoints = m["radfarm_checkpoint_seconds_count"];
  EXPECT_GE(checkpoints, 1);
  EXPECT_EQ(m["radfarm_checkpoint_seconds_bucket{le=\"+Inf\"}"], checkpoints);
  EXPECT_GT(m["radfarm_checkpoint_seconds_sum"], 0);
  EXPECT_TRUE(m.count("radfarm_store_queue_depth"));

  // The status JSON shows the same job and agent, and the event stream sends it.
  const nlohmann::json status = nlohmann::json::parse(Request("GET", "/api/status").body);
  ASSERT_EQ(status["jobs"].size(), 1u);
  EXPECT_EQ(status["jobs"][0]["state"], "done");
  EXPECT_EQ(status["jobs"][0]["progress"], 1.0);
  ASSERT_EQ(status["agents"].size(), 1u);
  EXPECT_EQ(status["agents"][0]["name"], "metrics-agent");
  EXPECT_FALSE(status["events"].empty());
  Result<std::string> stream =
      HttpReadUntil(address_, "/api/events", "\"metrics-agent\"", std::chrono::seconds(60));
  ASSERT_TRUE(stream.ok()) << stream.error();
  EXPECT_NE(stream->find("Content-Type: text/event-stream"), std::string::npos) << *stream;
  EXPECT_NE(stream->find("\r\n\r\nretry: 2000\n\nevent: status\ndata: {"), std::string::npos);

  // The preview of the finished job is a PNG.
  const HttpResponse preview = Request("GET", "/api/jobs/" + std::to_string(id) + "/preview.png");
  EXPECT_EQ(preview.status, 200) << preview.body;
  EXPECT_EQ(preview.headers.at("content-type"), "image/png");
  EXPECT_EQ(preview.body.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(Request("GET", "/api/jobs/999/preview.png").status, 404);

  // Previews were drawn afresh per request (the solution read, the scene meshed again). Now one
  // checkpoint is drawn once: concurrent requests after the first get the same bytes, undrawn.
  const std::string path = "/api/jobs/" + std::to_string(id) + "/preview.png";
  std::vector<std::thread> clients;
  std::vector<HttpResponse> answers(8);
  for (HttpResponse& answer : answers) {
    clients.emplace_back([&] {
      Result<HttpResponse> r = HttpRequest(address_, "GET", path, {});
      if (r.ok()) answer = *r;
    });
  }
  for (std::thread& t : clients) t.join();
  for (const HttpResponse& answer : answers) {
    EXPECT_EQ(answer.status, 200) << answer.body;
    EXPECT_EQ(answer.body, preview.body);
  }
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "job " + std::to_string(id) + ": preview of round",
                               "drawn in"),
            1u)
      << MasterLog();
}

// Progress ran backwards on the farm: status and the page climbed high in the first round and fell
// when the second began; the gather's rays stood still while its bar moved; the master's log
// counted rounds from 0 where status counted from 1. Sampled over a real job's life (its rounds,
// the final gather and the display) from `status` and the page's data: progress and rays never
// fall, and every round the log names is numbered from 1.
TEST_F(WebConsoleTest, ProgressAndRaysNeverFallOverAJobsLife) {
  address_ = StartMasterWithConsole(false, {"--local-round-rays", "0"});
  StartAgent("progress-agent");
  ASSERT_TRUE(farm_.WaitForAgents(1, std::chrono::seconds(60)));
  const int64_t id = Submit("cornell-box.toml");  // converges: shooting rounds, gather, display
  struct Series {
    double progress = 0;
    uint64_t rays = 0;
    size_t samples = 0;
    std::set<std::string> phases;
  } status, page;
  const auto take = [&](const nlohmann::json& job, Series& series, const char* from) {
    if (!job.is_object() || !job.contains("progress")) return;
    const double progress = job["progress"].get<double>();
    const uint64_t rays = job["rays"].get<uint64_t>();
    EXPECT_GE(progress, series.progress) << from << ": " << job.dump();
    EXPECT_GE(rays, series.rays) << from << ": " << job.dump();
    // 1 only once done: the display after the rounds is still to come.
    if (job["state"] != "done") {
      EXPECT_LT(progress, 1.0) << from << ": " << job.dump();
    }
    series.progress = progress;
    series.rays = rays;
    ++series.samples;
    if (job["phase"].is_string()) series.phases.insert(job["phase"].get<std::string>());
  };
  ASSERT_TRUE(WaitUntil(
      [&] {
        const nlohmann::json job = Status(id);
        take(job, status, "status");
        const nlohmann::json data =
            nlohmann::json::parse(Request("GET", "/api/status").body, nullptr, false);
        if (data.is_object() && data["jobs"].is_array()) {
          for (const nlohmann::json& j : data["jobs"]) {
            if (j["id"] == id) take(j, page, "page");
          }
        }
        return job.is_object() && job["state"] == "done";
      },
      kJobTimeout))
      << MasterLog();
  EXPECT_EQ(status.progress, 1.0);
  EXPECT_GE(status.samples, 3u);
  EXPECT_GE(page.samples, 3u);
  EXPECT_TRUE(status.phases.count("round")) << "no sample while a round ran";
  const std::string log = MasterLog();
  EXPECT_GE(CountLines(log, "round 1: "), 1u) << log;
  EXPECT_EQ(CountLines(log, "round 0"), 0u) << log;
}

TEST_F(WebConsoleTest, PauseResumeAndCancelNeedTheTokenAndChangeTheJob) {
  address_ = StartMasterWithConsole(true);
  // No agent: the job stays queued or running while we act on it.
  const int64_t id = Submit("cornell-box.toml");
  const std::string job = "/api/jobs/" + std::to_string(id);
  const std::string bearer = "Authorization: Bearer " + kToken;
  EXPECT_EQ(Request("POST", job + "/pause").status, 401);
  EXPECT_EQ(
      Request("POST", job + "/pause", {"Authorization: Bearer wrong-token-0123456789"}).status,
      401);
  EXPECT_EQ(Request("POST", job + "/pause", {bearer, "Host: rebound.example"}).status, 403);

  const HttpResponse paused = Request("POST", job + "/pause", {bearer});
  EXPECT_EQ(paused.status, 200) << paused.body;
  EXPECT_EQ(Status(id).value("state", ""), "paused");
  EXPECT_EQ(Request("POST", job + "/pause", {bearer}).status, 409);  // as `radfarm pause` refuses
  EXPECT_EQ(Request("POST", job + "/resume", {bearer}).status, 200);
  EXPECT_NE(Status(id).value("state", ""), "paused");
  EXPECT_EQ(Request("POST", job + "/cancel", {bearer}).status, 200);
  EXPECT_EQ(Status(id).value("state", ""), "cancelled");
  EXPECT_EQ(Request("POST", "/api/jobs/999/cancel", {bearer}).status, 404);
  // The store's event log, where `radfarm log` reads it, has the operator's actions.
  const CommandResult log = Cli({"log", std::to_string(id)});
  EXPECT_NE(log.out.find("cancel"), std::string::npos) << log.out;
}

// A cookie is sent to every port of a host, so a page served by another program on 127.0.0.1
// could replay a session cookie; a session goes only in the Authorization header.
TEST_F(WebConsoleTest, ASessionInACookieDoesNotActOnlyInTheAuthorizationHeaderUntilSignOut) {
  address_ = StartMasterWithConsole(true);
  const int64_t id = Submit("cornell-box.toml");
  const std::string job = "/api/jobs/" + std::to_string(id);
  Result<HttpResponse> signed_in = HttpRequest(
      address_, "POST", "/api/session", {"X-Radfarm-Request: 1", "Content-Type: application/json"},
      nlohmann::json{{"token", kToken}}.dump());
  ASSERT_TRUE(signed_in.ok()) << signed_in.error();
  ASSERT_EQ(signed_in->status, 200) << signed_in->body;
  EXPECT_EQ(signed_in->headers.count("set-cookie"), 0u);
  const std::string session = nlohmann::json::parse(signed_in->body).value("session", "");
  ASSERT_EQ(session.size(), 64u) << signed_in->body;

  // What a neighbouring page could replay: the old cookie, with the page's marker header.
  for (const std::string& cookie :
       {"Cookie: radfarm_session=" + session, "Cookie: radfarm_session=" + kToken}) {
    EXPECT_EQ(Request("POST", job + "/pause", {cookie, "X-Radfarm-Request: 1"}).status, 401);
  }
  EXPECT_NE(Status(id).value("state", ""), "paused");

  const std::string bearer = "Authorization: Bearer " + session;
  EXPECT_EQ(Request("POST", job + "/pause", {bearer}).status, 200);
  EXPECT_EQ(Status(id).value("state", ""), "paused");
  EXPECT_EQ(Request("DELETE", "/api/session", {bearer}).status, 200);
  EXPECT_EQ(Request("POST", job + "/resume", {bearer}).status, 401);
  EXPECT_EQ(Status(id).value("state", ""), "paused");
}

TEST_F(WebConsoleTest, WithoutATokenThePageIsReadOnly) {
  address_ = StartMasterWithConsole(false);
  const int64_t id = Submit("cornell-box.toml");
  const HttpResponse refused =
      Request("POST", "/api/jobs/" + std::to_string(id) + "/cancel", {"X-Radfarm-Request: 1"});
  EXPECT_EQ(refused.status, 403);
  EXPECT_NE(refused.body.find("--http-token-file"), std::string::npos);
  EXPECT_NE(Status(id).value("state", ""), "cancelled");
}

// The page as served, before its script has heard from the master: it says it is loading, not
// "No jobs yet" or "No agent is connected" (a farm it knows nothing of yet).
TEST_F(WebConsoleTest, ThePageSaysLoadingUntilItsFirstUpdate) {
  address_ = StartMasterWithConsole(false);
  const HttpResponse page = Request("GET", "/");
  ASSERT_EQ(page.status, 200);
  for (const char* loading : {"id=\"loading-jobs\"", "id=\"loading-agents\""}) {
    EXPECT_NE(page.body.find(loading), std::string::npos) << loading << " in " << page.body;
  }
  for (const char* empty : {"no-jobs", "no-agents"}) {
    const std::regex hidden(std::string("<p id=\"") + empty + "\"[^>]*\\bhidden\\b");
    EXPECT_TRUE(std::regex_search(page.body, hidden)) << empty << " shown in " << page.body;
  }
}

TEST_F(WebConsoleTest, AConsoleBeyondLoopbackWithoutATokenIsRefusedAtStart) {
  farm_.StartMaster({"--http", "0.0.0.0:0"}, std::chrono::seconds(5));
  EXPECT_EQ(farm_.master()->WaitExit(std::chrono::seconds(60)), 2);
  EXPECT_NE(MasterLog().find("needs --http-token-file"), std::string::npos) << MasterLog();
}

}  // namespace
}  // namespace radfarm::testing
