#include "bench/restart/big_checkpoints.h"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "store/job_store.h"
#include "testing/child_process.h"
#include "testing/loopback_farm.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

using Clock = std::chrono::steady_clock;

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string WriteJobFile(const std::string& dir, const BigJobOptions& o) {
  const std::string path = dir + "/big.toml";
  std::ofstream out(path);
  out << "scene = \"" << RADFARM_SOURCE_DIR
      << "/scenes/cornell-box.obj\"\n\n[mesh]\npatch_size = " << o.patch_size
      << "\n\n[solver]\nsampler = \"sobol\"\nseed = 1\ntolerance = 0.001\n";
  if (o.shot_rays > 0) out << "shot_rays = " << o.shot_rays << "\n";
  if (!out) throw std::runtime_error("cannot write " + path);
  return path;
}

struct Round {
  double seconds = 0;  // from its start to its last result (radfarmd) or its end (render)
  uint64_t rays = 0;
  // Its checkpoint, when it had one: bytes, and milliseconds copying the state from the solver
  // (radfarmd's compute thread), encoding, committing, and in all (render: its SaveRound;
  // radfarmd: from queueing on the store thread to the commit, pruning included).
  bool checkpoint = false;
  double bytes = 0, copy_ms = 0, encode_ms = 0, commit_ms = 0, total_ms = 0;
};

// The rounds radfarmd logged: "round R: N rays, unshot U%, S s" and
// "round R checkpoint: B bytes, copy C ms, encode E ms, commit M ms, queued to committed Q ms".
void ParseMasterLog(const std::string& log, std::map<uint32_t, Round>* rounds) {
  static const std::regex round_line(R"(round (\d+): (\d+) rays, unshot [0-9.]+%, ([0-9.e+-]+) s)");
  static const std::regex checkpoint_line(
      R"(round (\d+) checkpoint: (\d+) bytes, copy ([0-9.]+) ms, encode ([0-9.]+) ms, commit )"
      R"(([0-9.]+) ms, queued to committed ([0-9.]+) ms)");
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, round_line)) {
      Round& r = (*rounds)[std::stoul(m[1])];
      r.rays = std::stoull(m[2]);
      r.seconds = std::stod(m[3]);
    } else if (std::regex_search(line, m, checkpoint_line)) {
      Round& r = (*rounds)[std::stoul(m[1])];
      r.checkpoint = true;
      r.bytes = std::stod(m[2]);
      r.copy_ms = std::stod(m[3]);
      r.encode_ms = std::stod(m[4]);
      r.commit_ms = std::stod(m[5]);
      r.total_ms = std::stod(m[6]);
    }
  }
}

// The checkpoints render --db printed: "--db: round R checkpoint: B bytes in T ms (encode E,
// commit M)"; the rounds' times from its store.
std::map<uint32_t, Round> RenderRounds(const std::string& out, const std::string& db) {
  std::map<uint32_t, Round> rounds;
  static const std::regex line_re(
      R"(--db: round (\d+) checkpoint: (\d+) bytes in ([0-9.]+) ms \(encode ([0-9.]+), commit )"
      R"(([0-9.]+); the render waited ([0-9.]+) ms\))");
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, line_re)) continue;
    Round& r = rounds[std::stoul(m[1])];
    r.checkpoint = true;
    r.bytes = std::stod(m[2]);
    r.total_ms = std::stod(m[3]);
    r.encode_ms = std::stod(m[4]);
    r.commit_ms = std::stod(m[5]);
    r.copy_ms = std::stod(m[6]);
  }
  Result<store::JobStore> s = store::JobStore::Open(db);
  if (!s) throw std::runtime_error(s.error());
  Result<std::vector<store::RoundRecord>> rows = s->ListRounds(1);
  if (!rows) throw std::runtime_error(rows.error());
  for (const store::RoundRecord& row : *rows) {
    rounds[row.round].seconds = row.duration_seconds;
    rounds[row.round].rays = row.rays;
  }
  return rounds;
}

struct Run {
  double seconds = 0;
  std::map<uint32_t, Round> rounds;
  std::string patches;
  // The killed run: the round after which the master was killed, and seconds from its restart
  // to the job prepared again (meshed, state loaded) and to its first round's end.
  int64_t killed_after_round = -1;
  double resume_prepared_seconds = 0, resume_first_round_seconds = 0;
};

Run RunRender(const BigJobOptions& o, const std::string& job, const std::string& dir) {
  const std::string out = dir + "/render", db = dir + "/render.db";
  const auto start = Clock::now();
  const testing::CommandResult r =
      testing::RunCommand({RADFARM_CLI_PATH, "render", job, "--out", out, "--db", db, "--rays",
                           std::to_string(o.rays), "--threads", std::to_string(o.agents)});
  Run run;
  run.seconds = Since(start);
  if (r.exit_code != 0) throw std::runtime_error("render failed: " + r.err);
  run.rounds = RenderRounds(r.out, db);
  run.patches = ReadFile(out + "/patches.csv");
  return run;
}

bool HasRoundLine(const std::string& log) {
  static const std::regex round_line(R"(round \d+: \d+ rays)");
  return std::regex_search(log, round_line);
}

}  // namespace

std::string StartMasterAndAgents(testing::LoopbackFarm& farm, const std::vector<std::string>& flags,
                                 unsigned agents) {
  farm.StartMaster(flags);
  if (farm.master_address().empty()) throw std::runtime_error("radfarmd: " + farm.MasterLog());
  for (unsigned k = 0; k < agents; ++k) farm.StartAgent("a" + std::to_string(k), 1);
  if (!farm.WaitForAgents(agents, std::chrono::seconds(60))) {
    throw std::runtime_error("agents did not connect");
  }
  return "127.0.0.1:" + farm.master_address().substr(farm.master_address().rfind(':') + 1);
}

namespace {

Run RunFarm(const BigJobOptions& o, const std::string& job, const std::string& dir, bool kill) {
  const std::string farm_dir = dir + (kill ? "/farm-killed" : "/farm");
  std::filesystem::create_directories(farm_dir);
  testing::LoopbackFarm farm({RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, farm_dir);
  std::vector<std::string> flags = {"--log-level", "info"};
  std::istringstream extra(o.checkpoint_flags);
  for (std::string flag; extra >> flag;) flags.push_back(flag);
  const std::string listen = StartMasterAndAgents(farm, flags, o.agents);
  std::string error;
  const auto start = Clock::now();
  const int64_t id = farm.Submit(job, {"--rays", std::to_string(o.rays)}, &error);
  if (id < 0) throw std::runtime_error("submit: " + error);
  Run run;
  if (kill) {
    // Kill once the first checkpoint after round 0 is committed: mid-job, a round running.
    std::map<uint32_t, Round> seen;
    const auto give_up = Clock::now() + std::chrono::minutes(30);
    while (true) {
      seen.clear();
      ParseMasterLog(farm.MasterLog(), &seen);
      const auto it = std::find_if(seen.begin(), seen.end(), [](const auto& r) {
        return r.first >= 1 && r.second.checkpoint;
      });
      if (it != seen.end()) {
        run.killed_after_round = it->first;
        break;
      }
      if (Clock::now() > give_up) throw std::runtime_error("no checkpoint after round 0");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // polling the log
    }
    farm.master()->Signal(SIGKILL);
    if (!farm.master()->WaitExit(std::chrono::seconds(30))) throw std::runtime_error("no exit");
    ParseMasterLog(farm.MasterLog(), &run.rounds);
    std::filesystem::remove(farm.state_dir() + "/http.addr");
    std::vector<std::string> again = flags;
    again.insert(again.end(), {"--listen", listen});
    // The new master's lines only (it appends to the old one's log).
    const size_t old_log = farm.MasterLog().size();
    auto new_log = [&] {
      const std::string log = farm.MasterLog();
      return log.size() > old_log ? log.substr(old_log) : std::string();
    };
    const auto restarted = Clock::now();
    farm.StartMaster(again);
    if (farm.master_address().empty()) throw std::runtime_error("restart: " + farm.MasterLog());
    while (new_log().find(" compressed)") == std::string::npos) {
      if (Clock::now() > give_up) throw std::runtime_error("the job never started again");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    run.resume_prepared_seconds = Since(restarted);
    while (!HasRoundLine(new_log())) {
      if (Clock::now() > give_up) throw std::runtime_error("no round after the restart");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    run.resume_first_round_seconds = Since(restarted);
  }
  const nlohmann::json done = farm.WaitForJob(id, testing::IsFinished, std::chrono::minutes(60),
                                              std::chrono::milliseconds(200));
  run.seconds = Since(start);
  if (done.value("state", std::string()) != "done") {
    throw std::runtime_error("job ended " + done.dump() + "\n" + farm.MasterLog());
  }
  ParseMasterLog(farm.MasterLog(), &run.rounds);
  const std::string out = farm.File("out");
  if (farm.Fetch(id, out).exit_code != 0) throw std::runtime_error("fetch failed");
  run.patches = ReadFile(out + "/patches.csv");
  return run;
}

nlohmann::json Summary(const char* name, const Run& run) {
  nlohmann::json rounds = nlohmann::json::array();
  std::vector<double> bytes, total, critical, share, waited_share;
  double all_bytes = 0, all_checkpoint_seconds = 0, all_round_seconds = 0;
  for (const auto& [index, r] : run.rounds) {
    rounds.push_back({{"round", index},
                      {"seconds", r.seconds},
                      {"rays", r.rays},
                      {"checkpoint", r.checkpoint},
                      {"bytes", r.bytes},
                      {"copy_ms", r.copy_ms},
                      {"encode_ms", r.encode_ms},
                      {"commit_ms", r.commit_ms},
                      {"total_ms", r.total_ms}});
    all_round_seconds += r.seconds;
    if (!r.checkpoint) continue;
    all_checkpoint_seconds += r.total_ms / 1000;
    bytes.push_back(r.bytes);
    total.push_back(r.total_ms);
    // What the solve waits for: the copy of the state (render's main thread, radfarmd's compute
    // thread); the writer's or store thread writes it while the next round runs.
    critical.push_back(r.copy_ms);
    all_bytes += r.bytes;
    if (r.seconds > 0) share.push_back(r.total_ms / 1000 / r.seconds);
    if (r.seconds > 0) waited_share.push_back(r.copy_ms / 1000 / r.seconds);
  }
  size_t checkpoints = bytes.size();
  const double bytes_per_round = run.rounds.empty() ? 0 : all_bytes / run.rounds.size();
  // What checkpoints cost the job in all: their writing against the rounds' time, rounds without
  // one included (the master writes one only once it has run 20 times as long as the last took).
  const double share_of_rounds =
      all_round_seconds > 0 ? all_checkpoint_seconds / all_round_seconds : 0;
  std::printf("%-22s %8.1f %7zu %12zu %12.1f %12.1f %12.1f%% %14.1f %12.2f%% %12.1f%%\n", name,
              run.seconds, run.rounds.size(), checkpoints, bytes_per_round / 1e6, Median(total),
              100 * Median(share), Median(critical), 100 * Median(waited_share),
              100 * share_of_rounds);
  std::fflush(stdout);
  return {{"name", name},
          {"seconds", run.seconds},
          {"rounds", rounds},
          {"checkpoints", checkpoints},
          {"median_checkpoint_bytes", Median(bytes)},
          {"median_checkpoint_ms", Median(total)},
          {"median_waited_ms", Median(critical)},
          {"median_checkpoint_share_of_round", Median(share)},
          {"median_waited_share_of_round", Median(waited_share)},
          {"checkpoint_bytes_per_round", bytes_per_round},
          {"checkpoint_share_of_all_rounds", share_of_rounds},
          {"killed_after_round", run.killed_after_round},
          {"resume_prepared_seconds", run.resume_prepared_seconds},
          {"resume_first_round_seconds", run.resume_first_round_seconds}};
}

}  // namespace

nlohmann::json MeasureBigJobCheckpoints(const BigJobOptions& o) {
  testing::TempDir dir;
  const std::string job = WriteJobFile(dir.path(), o);
  std::printf("\nCornell box at patch size %g mm, %llu rays%s; %u agents x 1 thread\n",
              o.patch_size, static_cast<unsigned long long>(o.rays),
              o.shot_rays ? (", shot_rays " + std::to_string(o.shot_rays)).c_str() : "", o.agents);
  // Medians over the checkpoints; "waited": what the solve waited for (the state's copy).
  std::printf("%-22s %8s %7s %12s %12s %12s %13s %14s %13s %13s\n", "run", "seconds", "rounds",
              "checkpoints", "MB/round", "ms", "% of round", "waited ms", "% of round",
              "% of rounds");
  nlohmann::json runs = nlohmann::json::array();
  const Run render = RunRender(o, job, dir.path());
  runs.push_back(Summary("render --db", render));
  const Run farm = RunFarm(o, job, dir.path(), false);
  runs.push_back(Summary("farm", farm));
  const Run killed = RunFarm(o, job, dir.path(), true);
  runs.push_back(Summary("farm, master killed", killed));
  const bool same_farm = killed.patches == farm.patches,
             same_render = farm.patches == render.patches;
  std::printf(
      "master SIGKILLed after round %lld's checkpoint; restarted, job prepared in %.1f s, "
      "first round done %.1f s after the restart\n",
      static_cast<long long>(killed.killed_after_round), killed.resume_prepared_seconds,
      killed.resume_first_round_seconds);
  std::printf("patches.csv: killed run %s the farm run without kills, which %s render's\n",
              same_farm ? "equals" : "DIFFERS FROM", same_render ? "equals" : "DIFFERS FROM");
  if (!same_farm) throw std::runtime_error("the killed run's patches.csv differs");
  return {{"patch_size", o.patch_size},
          {"rays", o.rays},
          {"shot_rays", o.shot_rays},
          {"agents", o.agents},
          {"checkpoint_flags", o.checkpoint_flags},
          {"patches", std::count(farm.patches.begin(), farm.patches.end(), '\n') - 1},
          {"runs", runs},
          {"killed_equals_unkilled", same_farm},
          {"farm_equals_render", same_render}};
}

}  // namespace radfarm::bench
