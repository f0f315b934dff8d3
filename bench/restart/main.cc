// restart_bench: what a master crash costs a job (a job whose master was killed 12
// times took 22 s instead of 4-9 s). A loopback farm (radfarmd and agents) solves the same job
//   - without kills,
//   - with the master SIGKILLed and restarted --kills times mid-round, keeping no round results
//     (--keep-round-results false: what a restart cost before they were kept),
//   - the same, keeping every result from the round's start (--keep-results-after 0),
//   - without kills, keeping them after 5 s (the default, which a Cornell box round never reaches),
// --runs times each (and without kills, not keeping, for the cost of keeping), and prints the
// medians of the wall time and of the batch results accepted beyond the run without kills: work
// computed again because a master forgot it (a Cornell box round holds 2,800-3,800 batches). Every
// job must end byte-identical to the run without kills. A kill waits until the new master has
// accepted
// --kill-after results, so it lands mid-round or just after a round, as a crash would.
// It also measures what the store absorbs: JobStore::SaveRoundResults of results the size of
// this job's, one per transaction and in groups, against the results per second the farm made.
// With --big-patch-size it also measures what checkpoints cost a big job and that a master killed
// on it resumes byte-identical (big_checkpoints.h); --big-only runs that alone.
// Writes bench/results/restart_bench.json.
//
//   restart_bench [--kills 6] [--runs 3] [--agents 2] [--kill-after 1500] [--json PATH]
//                 [--big-patch-size 1.45 [--big-rays N] [--big-shot-rays N] [--big-only]]
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/restart/big_checkpoints.h"
#include "store/job_store.h"
#include "testing/http_client.h"
#include "testing/loopback_farm.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  int kills = 6;
  int runs = 3;
  unsigned agents = 2;
  double kill_after = 1500;  // results accepted by the current master before it is killed
  std::string json = DefaultJsonPath("restart_bench");
  std::optional<BigJobOptions> big;  // --big-patch-size given
  bool big_only = false;
};

Options Parse(int argc, char** argv) {
  Options o;
  bool json_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--kills") {
      o.kills = std::stoi(next());
    } else if (a == "--runs") {
      o.runs = std::stoi(next());
    } else if (a == "--agents") {
      o.agents = static_cast<unsigned>(std::stoul(next()));
    } else if (a == "--kill-after") {
      o.kill_after = std::stod(next());
    } else if (a == "--json") {
      o.json = next();
      json_given = true;
    } else if (a == "--big-patch-size") {
      if (!o.big) o.big.emplace();
      o.big->patch_size = std::stod(next());
    } else if (a == "--big-rays") {
      if (!o.big) o.big.emplace();
      o.big->rays = std::stoull(next());
    } else if (a == "--big-shot-rays") {
      if (!o.big) o.big.emplace();
      o.big->shot_rays = std::stoull(next());
    } else if (a == "--big-flags") {
      if (!o.big) o.big.emplace();
      o.big->checkpoint_flags = next();
    } else if (a == "--big-only") {
      o.big_only = true;
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "restart_bench [--kills N] [--runs N] [--agents N] [--kill-after N] [--json PATH]\n"
          "  A Cornell box job on a loopback farm without kills, and with N master SIGKILLs\n"
          "  (each after the new master accepted --kill-after results), with and without the\n"
          "  round's results kept in the store; medians of --runs runs. Writes\n"
          "  bench/results/restart_bench.json unless --json says where.\n"
          "  --big-patch-size MM: also the Cornell box at that patch size (1.45: 1,046,925\n"
          "  patches) with --big-rays N (default 50000000) and --big-shot-rays N ([solver]\n"
          "  shot_rays, default automatic), by render --db and by the farm with and without one\n"
          "  master SIGKILL: each checkpoint's bytes and times against its round's; --big-flags\n"
          "  'FLAGS' passes radfarmd flags; --big-only skips the Cornell box runs and writes\n"
          "  bench/results/restart_bench_big.json.\n");
      std::exit(0);
    } else {
      throw std::runtime_error("unknown argument " + a + " (see --help)");
    }
  }
  if (o.runs < 1 || o.kills < 0) throw std::runtime_error("--runs >= 1, --kills >= 0");
  if (o.big_only && !o.big) throw std::runtime_error("--big-only needs --big-patch-size");
  // Its own file, so the Cornell box's figures stay.
  if (o.big_only && !json_given) o.json = DefaultJsonPath("restart_bench_big");
  return o;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// /metrics of the master's console as name -> value (labelled series left out).
std::map<std::string, double> Scrape(const std::string& state_dir) {
  std::string address = ReadFile(state_dir + "/http.addr");
  address = address.substr(0, address.find('\n'));
  std::map<std::string, double> values;
  if (address.empty()) return values;
  Result<testing::HttpResponse> r =
      testing::HttpRequest(address, "GET", "/metrics", {}, "", std::chrono::seconds(10));
  if (!r || r->status != 200) return values;
  std::istringstream lines(r->body);
  const std::regex sample(R"(^([a-z_]+) (\S+)$)");
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, sample)) values[m[1]] = std::stod(m[2]);
  }
  return values;
}

struct RunResult {
  double seconds = 0;
  double batches_issued = 0;  // over every master of the run
  double batches_restored = 0;
  double results_accepted = 0;
  double results_kept = 0, result_writes = 0;  // of the last master
  std::string patches;
};

// keep_after: --keep-results-after, or negative for --keep-round-results false.
RunResult RunJob(const Options& o, int kills, double keep_after) {
  testing::TempDir dir;
  testing::LoopbackFarm farm({RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, dir.path());
  std::vector<std::string> flags = {"--log-level",
                                    "warning",
                                    "--http",
                                    "127.0.0.1:0",
                                    "--keep-round-results",
                                    keep_after >= 0 ? "true" : "false"};
  if (keep_after >= 0) {
    flags.insert(flags.end(), {"--keep-results-after", std::to_string(keep_after)});
  }
  const std::string listen = StartMasterAndAgents(farm, flags, o.agents);
  std::string error;
  const auto start = Clock::now();
  const int64_t id =
      farm.Submit(std::string(RADFARM_SOURCE_DIR) + "/scenes/cornell-box.toml", {}, &error);
  if (id < 0) throw std::runtime_error("submit: " + error);
  RunResult run;
  auto add_master = [&](const std::map<std::string, double>& m) {
    auto value = [&](const char* name) { return m.count(name) ? m.at(name) : 0.0; };
    run.batches_issued += value("radfarm_batches_issued_total");
    run.batches_restored += value("radfarm_batches_restored_total");
    run.results_accepted += value("radfarm_batch_results_accepted_total");
    run.results_kept = value("radfarm_round_results_kept_total");
    run.result_writes = value("radfarm_round_result_writes_total");
  };
  std::map<std::string, double> last;
  for (int kill = 0; kill < kills; ++kill) {
    const nlohmann::json job = farm.WaitForJob(
        id,
        [&](const nlohmann::json& j) {
          if (testing::IsFinished(j)) return true;
          last = Scrape(farm.state_dir());
          return last["radfarm_batch_results_accepted_total"] >= o.kill_after;
        },
        std::chrono::seconds(600), std::chrono::milliseconds(5));
    if (testing::IsFinished(job)) break;
    farm.master()->Signal(SIGKILL);
    if (!farm.master()->WaitExit(std::chrono::seconds(30))) throw std::runtime_error("no exit");
    add_master(last);  // the figures just before the kill (a few results may have come since)
    std::filesystem::remove(farm.state_dir() + "/http.addr");
    std::vector<std::string> again = flags;
    again.insert(again.end(), {"--listen", listen});
    farm.StartMaster(again);
    if (farm.master_address().empty()) throw std::runtime_error("restart: " + farm.MasterLog());
  }
  const nlohmann::json done = farm.WaitForJob(id, testing::IsFinished, std::chrono::seconds(900));
  run.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (done.value("state", std::string()) != "done") {
    throw std::runtime_error("job ended " + done.dump() + "\n" + farm.MasterLog());
  }
  add_master(Scrape(farm.state_dir()));
  const std::string out = farm.File("out");
  if (farm.Fetch(id, out).exit_code != 0) throw std::runtime_error("fetch failed");
  run.patches = ReadFile(out + "/patches.csv");
  return run;
}

// Results per second SaveRoundResults commits in groups of `group`, results of `hits` hits.
double StoreAbsorbs(size_t group, size_t hits) {
  testing::TempDir dir;
  Result<store::JobStore> s = store::JobStore::Open(dir.File("radfarm.db"));
  if (!s) throw std::runtime_error(s.error());
  if (Status put = s->PutScene("scene", std::vector<uint8_t>{1}); !put) {
    throw std::runtime_error(put.error());
  }
  const store::JobId job = *s->SubmitJob({"bench", "scene", "", 1, 0});
  std::vector<store::StoredBatchResult> results(group);
  uint32_t index = 0;
  const auto start = Clock::now();
  size_t written = 0;
  while (written < 256 || Clock::now() - start < std::chrono::seconds(2)) {
    for (store::StoredBatchResult& r : results) {
      r.index = index++;
      r.batch = {0, r.index, 0, 4096};
      r.result.hits.clear();
      for (uint32_t h = 0; h < hits; ++h) r.result.hits.push_back({h * 3, 1 + h});
    }
    if (Status w = s->SaveRoundResults(job, results); !w) throw std::runtime_error(w.error());
    written += group;
  }
  return double(written) / std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  using namespace radfarm::bench;
  try {
    const Options o = Parse(argc, argv);
    const MachineInfo machine = ReadMachineInfo(argc, argv);
    struct Mode {
      const char* name;
      int kills;
      double keep_after;  // negative: not kept
      bool keep() const { return keep_after >= 0; }
    };
    std::vector<Mode> modes = {{"no kills, all kept", 0, 0},
                               {"no kills, kept after 5 s", 0, 5},
                               {"no kills, not kept", 0, -1},
                               {"kills, not kept", o.kills, -1},
                               {"kills, all kept", o.kills, 0}};
    if (o.big_only) modes.clear();
    nlohmann::json json{{"machine", MachineJson(machine)},
                        {"kills", o.kills},
                        {"runs", o.runs},
                        {"agents", o.agents},
                        {"kill_after", o.kill_after}};
    std::string reference;
    double baseline_accepted = -1, produced_per_second = 0;
    if (!o.big_only)
      std::printf("%-24s %8s %10s %10s %14s %10s\n", "mode", "seconds", "leased", "accepted",
                  "computed again", "restored");
    for (const Mode& mode : modes) {
      std::vector<double> seconds, issued, accepted, restored;
      double kept = 0, writes = 0;
      for (int run = 0; run < o.runs; ++run) {
        const RunResult r = RunJob(o, mode.kills, mode.keep_after);
        if (reference.empty()) reference = r.patches;
        if (r.patches != reference)
          throw std::runtime_error(std::string(mode.name) + ": bytes differ");
        seconds.push_back(r.seconds);
        issued.push_back(r.batches_issued);
        accepted.push_back(r.results_accepted);
        restored.push_back(r.batches_restored);
        if (mode.kills == 0 && mode.keep_after == 0) {
          produced_per_second = std::max(produced_per_second, r.results_accepted / r.seconds);
          kept += r.results_kept;
          writes += r.result_writes;
        }
      }
      if (baseline_accepted < 0) baseline_accepted = Median(accepted);
      const double again = Median(accepted) - baseline_accepted;
      std::printf("%-24s %8.2f %10.0f %10.0f %14.0f %10.0f\n", mode.name, Median(seconds),
                  Median(issued), Median(accepted), again, Median(restored));
      json["modes"].push_back({{"mode", mode.name},
                               {"kills", mode.kills},
                               {"keep_round_results", mode.keep()},
                               {"keep_results_after_seconds", mode.keep_after},
                               {"seconds", seconds},
                               {"batches_issued", issued},
                               {"results_accepted", accepted},
                               {"batches_restored", restored},
                               {"median_seconds", Median(seconds)},
                               {"median_results_computed_again", again}});
      if (mode.kills == 0 && mode.keep_after == 0 && writes > 0) {
        std::printf("  without kills: %.0f results/s accepted, kept in %.1f results a write\n",
                    produced_per_second, kept / writes);
        json["farm_results_per_second"] = produced_per_second;
        json["results_per_write"] = kept / writes;
      }
    }
    if (o.big) json["big_job"] = MeasureBigJobCheckpoints(*o.big);
    if (!o.big_only) std::printf("\n%-10s %22s\n", "group", "store results/s");
    for (size_t group : {size_t{1}, size_t{8}, size_t{32}, size_t{128}}) {
      if (o.big_only) break;
      const double rate = StoreAbsorbs(group, 400);
      std::printf("%-10zu %22.0f\n", group, rate);
      json["store"].push_back({{"group", group}, {"hits", 400}, {"results_per_second", rate}});
    }
    WriteJson(o.json, json);
    std::printf("wrote %s\n", o.json.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "restart_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
