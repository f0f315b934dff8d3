#include "bench/restart/big_checkpoints.h"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
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

// The last checkpoint in a job object of radfarmd (`radfarm status --json`, docs/CONTROL.md):
// its figures go to its round. `committed` counts the master's checkpoints of the job, so one
// committed between two looks is counted as missed rather than lost without a word.
struct CheckpointWatch {
  uint64_t committed = 0;  // the current master's count at the last look
  uint64_t missed = 0;

  void Take(const nlohmann::json& job, std::map<uint32_t, Round>* rounds) {
    const nlohmann::json& c = job.value("last_checkpoint", nlohmann::json());
    if (!c.is_object()) return;
    const uint64_t now = c.value("committed", uint64_t{0});
    if (now == committed) return;
    // A restarted master counts from 1 again.
    missed += now > committed ? now - committed - 1 : now - 1;
    committed = now;
    // Shown from 1 (core/progressive_solver.h ShownRound); the store's rows are the plan's.
    Round& r = (*rounds)[c.value("round", 1u) - 1];
    r.checkpoint = true;
    r.bytes = c.value("bytes", 0.0);
    r.copy_ms = c.value("copy_ms", 0.0);
    r.encode_ms = c.value("encode_ms", 0.0);
    r.commit_ms = c.value("commit_ms", 0.0);
    r.total_ms = c.value("queued_ms", 0.0);
  }
};

// The rounds' wall times and rays, from job `id`'s rows in the store at `db`.
void AddStoreRounds(const std::string& db, int64_t id, std::map<uint32_t, Round>* rounds) {
  Result<store::JobStore> s = store::JobStore::Open(db);
  if (!s) throw std::runtime_error(s.error());
  Result<std::vector<store::RoundRecord>> rows = s->ListRounds(store::JobId(id));
  if (!rows) throw std::runtime_error(rows.error());
  for (const store::RoundRecord& row : *rows) {
    (*rounds)[row.round].seconds = row.duration_seconds;
    (*rounds)[row.round].rays = row.rays;
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
    Round& r = rounds[std::stoul(m[1]) - 1];  // shown from 1, the store's rows from 0
    r.checkpoint = true;
    r.bytes = std::stod(m[2]);
    r.total_ms = std::stod(m[3]);
    r.encode_ms = std::stod(m[4]);
    r.commit_ms = std::stod(m[5]);
    r.copy_ms = std::stod(m[6]);
  }
  AddStoreRounds(db, 1, &rounds);
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
  uint64_t checkpoints_missed = 0;  // committed between two looks at the job (CheckpointWatch)
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
  CheckpointWatch watch;
  // Looks at the job through `radfarm status --json` until `until` holds or the job ends.
  auto wait = [&](const std::function<bool(const nlohmann::json&)>& until,
                  std::chrono::minutes timeout) {
    return farm.WaitForJob(
        id,
        [&](const nlohmann::json& j) {
          watch.Take(j, &run.rounds);
          return testing::IsFinished(j) || until(j);
        },
        timeout, std::chrono::milliseconds(100));
  };
  if (kill) {
    // Kill once the first checkpoint after round 0 is committed: mid-job, a round running.
    const nlohmann::json at = wait(
        [](const nlohmann::json& j) {
          const nlohmann::json& c = j.value("last_checkpoint", nlohmann::json());
          return c.is_object() && c.value("round", 1u) >= 2;
        },
        std::chrono::minutes(30));
    if (testing::IsFinished(at)) throw std::runtime_error("no checkpoint after round 0");
    run.killed_after_round = at["last_checkpoint"].value("round", 1u) - 1;
    farm.master()->Signal(SIGKILL);
    if (!farm.master()->WaitExit(std::chrono::seconds(30))) throw std::runtime_error("no exit");
    std::filesystem::remove(farm.state_dir() + "/http.addr");
    std::vector<std::string> again = flags;
    again.insert(again.end(), {"--listen", listen});
    const auto restarted = Clock::now();
    farm.StartMaster(again);
    if (farm.master_address().empty()) throw std::runtime_error("restart: " + farm.MasterLog());
    // Prepared again (meshed, its state loaded): its phase is past "preparing".
    const nlohmann::json prepared = wait(
        [](const nlohmann::json& j) {
          const nlohmann::json& phase = j.value("phase", nlohmann::json());
          return phase.is_string() && phase != "preparing";
        },
        std::chrono::minutes(30));
    run.resume_prepared_seconds = Since(restarted);
    const uint32_t resumed_at = prepared.value("round", 0u);
    wait([&](const nlohmann::json& j) { return j.value("round", 0u) > resumed_at; },
         std::chrono::minutes(30));
    run.resume_first_round_seconds = Since(restarted);
  }
  const nlohmann::json done =
      wait([](const nlohmann::json&) { return false; }, std::chrono::minutes(60));
  run.seconds = Since(start);
  if (done.value("state", std::string()) != "done") {
    throw std::runtime_error("job ended " + done.dump() + "\n" + farm.MasterLog());
  }
  run.checkpoints_missed = watch.missed;
  AddStoreRounds(farm.state_dir() + "/radfarm.db", id, &run.rounds);
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
          {"resume_first_round_seconds", run.resume_first_round_seconds},
          {"checkpoints_missed", run.checkpoints_missed}};
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
