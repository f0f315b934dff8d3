// budget_bench: does `radfarm render` keep to its budget on a scene big enough to need one (issue
// 21: budgets hold from the first second)? Renders the Cornell box cut into fine patches
// (--patch-size 5: 88,750 patches, its light 546 of them) with each time budget and each ray
// budget given, 2 threads, and reports where the time went (meshing, the direct-light start and
// its shadow rays, the rounds, the display after the solve) and, against one render without a
// budget, each run's error per patch. Prints a table and writes bench/results/budget_bench.json.
//
//   budget_bench [--seconds LIST] [--rays LIST] [--patch-size P] [--no-reference] [--json PATH]
//                [--keep DIR]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/memory/peak_rss.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

struct Options {
  std::vector<double> seconds = {5, 10, 20};
  std::vector<uint64_t> rays = {30000000};
  double patch_size = 5;
  bool reference = true;
  std::string json = DefaultJsonPath("budget_bench");
  std::string keep;  // write the outputs and logs here instead of a temporary directory
};

template <typename T>
std::vector<T> ParseList(const std::string& text, T (*parse)(const std::string&)) {
  std::vector<T> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) out.push_back(parse(item));
  return out;
}

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--seconds") {
      o.seconds = ParseList<double>(next(), [](const std::string& s) { return std::stod(s); });
    } else if (a == "--rays") {
      o.rays = ParseList<uint64_t>(
          next(), [](const std::string& s) { return static_cast<uint64_t>(std::stoull(s)); });
    } else if (a == "--patch-size") {
      o.patch_size = std::stod(next());
    } else if (a == "--no-reference") {
      o.reference = false;
    } else if (a == "--json") {
      o.json = next();
    } else if (a == "--keep") {
      o.keep = next();
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "budget_bench [--seconds LIST] [--rays LIST] [--patch-size P] [--no-reference]\n"
          "             [--json PATH] [--keep DIR]\n"
          "  radfarm render of scenes/cornell-box.toml at --patch-size P (default 5: 88,750\n"
          "  patches) on 2 threads with each time budget of LIST (default 5,10,20 seconds) and\n"
          "  each ray budget of LIST (default 30000000): wall time, meshing, the direct-light\n"
          "  start, the solve and the display, and, against a render without a budget (skipped\n"
          "  with --no-reference), the error per patch of patches.csv. Writes\n"
          "  bench/results/budget_bench.json unless --json says where. --keep DIR: keep the\n"
          "  outputs and logs under DIR.\n");
      std::exit(0);
    } else {
      throw std::runtime_error("unknown argument " + a + " (see --help)");
    }
  }
  if (!(o.patch_size > 0)) throw std::runtime_error("--patch-size: must be positive");
  return o;
}

// The number after `marker` in `text` ("read and meshed in 1.0 s"), or 0 when absent.
double NumberAfter(const std::string& text, const std::string& marker) {
  const size_t at = text.find(marker);
  return at == std::string::npos ? 0 : std::strtod(text.c_str() + at + marker.size(), nullptr);
}

// testing::ReadFile gives "" for a file it cannot read.
std::string ReadText(const std::string& path) {
  std::string text = testing::ReadFile(path);
  if (text.empty()) throw std::runtime_error(path + ": cannot read");
  return text;
}

// Per patch of patches.csv: area and the radiosity's channel sum.
struct PatchValues {
  std::vector<double> area, value;
};

PatchValues ReadPatches(const std::string& path) {
  std::istringstream in(ReadText(path));
  std::string line;
  std::getline(in, line);  // patch,surface,material,area,cx,cy,cz,nx,ny,nz,r,g,b
  PatchValues out;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (cells.size() != 13) throw std::runtime_error(path + ": a row without 13 cells");
    out.area.push_back(std::stod(cells[3]));
    out.value.push_back(std::stod(cells[10]) + std::stod(cells[11]) + std::stod(cells[12]));
  }
  return out;
}

// Against the reference, over the patches it lights: the median and 95th percentile of the
// relative error per patch, and the area-weighted bias of the light.
struct PatchErrors {
  double median = 0, p95 = 0, bias = 0;
};

PatchErrors Errors(const PatchValues& run, const PatchValues& reference) {
  if (run.value.size() != reference.value.size()) {
    throw std::runtime_error("a run and the reference differ in patches");
  }
  std::vector<double> relative;
  double difference = 0, total = 0;
  for (size_t i = 0; i < run.value.size(); ++i) {
    const double ref = reference.value[i];
    if (!(ref > 0)) continue;
    relative.push_back(std::abs(run.value[i] - ref) / ref);
    difference += reference.area[i] * (run.value[i] - ref);
    total += reference.area[i] * ref;
  }
  PatchErrors e;
  if (relative.empty()) return e;
  std::sort(relative.begin(), relative.end());
  e.median = relative[relative.size() / 2];
  e.p95 = relative[std::min(relative.size() - 1, relative.size() * 95 / 100)];
  e.bias = total > 0 ? difference / total : 0;
  return e;
}

struct Budget {
  std::string flag;  // --seconds or --rays, or empty: none
  std::string value;
  std::string name;
};

nlohmann::json RenderWith(const Budget& budget, const Options& o, const std::string& dir) {
  const std::string out = dir + "/" + budget.name;
  const std::string log = out + ".log";
  char patch_size[32];
  std::snprintf(patch_size, sizeof patch_size, "%g", o.patch_size);
  std::vector<std::string> args = {
      RADFARM_CLI_PATH, "render",    RADFARM_SOURCE_DIR "/scenes/cornell-box.toml",
      "--out",          out,         "--patch-size",
      patch_size,       "--threads", "2"};
  if (!budget.flag.empty()) {
    args.push_back(budget.flag);
    args.push_back(budget.value);
  }
  const MeasuredRun run = RunMeasured(args, log);
  if (run.exit_code != 0) throw std::runtime_error("render failed: see " + log);
  const nlohmann::json stats = nlohmann::json::parse(ReadText(out + "/stats.json"));
  const std::string text = ReadText(log);
  return {{"budget", budget.name},
          {"patches", stats.at("patches")},
          {"wall_seconds", run.seconds},
          {"mesh_seconds", NumberAfter(text, "read and meshed in ")},
          // Printed from half a second on; the solve's seconds include it either way.
          {"start_seconds", stats.value("start_seconds", 0.0)},
          {"start_rays", stats.value("start_rays", uint64_t{0})},
          {"solve_seconds", stats.at("seconds")},
          {"rays", stats.at("rays")},
          {"rounds", stats.at("rounds")},
          {"unshot_fraction", stats.at("unshot_fraction")},
          {"stop_reason", stats.at("stop_reason")},
          {"display_seconds", stats.value("display_seconds", 0.0)},
          {"display_rays", stats.value("display_rays", 0.0)},
          {"patches_csv", out + "/patches.csv"}};
}

int Main(int argc, char** argv) {
  const Options o = Parse(argc, argv);
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  std::optional<testing::TempDir> temp;
  if (o.keep.empty()) temp.emplace("budget_bench");
  const std::string root = o.keep.empty() ? temp->path() : o.keep;
  std::filesystem::create_directories(root);
  std::vector<Budget> budgets;
  for (double s : o.seconds) {
    char value[32];
    std::snprintf(value, sizeof value, "%g", s);
    budgets.push_back({"--seconds", value, std::string("seconds-") + value});
  }
  for (uint64_t r : o.rays) {
    budgets.push_back({"--rays", std::to_string(r), "rays-" + std::to_string(r)});
  }
  std::optional<PatchValues> reference;
  nlohmann::json reference_run;
  if (o.reference) {
    std::printf("rendering the reference (no budget) ...\n");
    std::fflush(stdout);
    reference_run = RenderWith({"", "", "reference"}, o, root);
    reference = ReadPatches(reference_run.at("patches_csv").get<std::string>());
    std::printf("reference: %llu patches, %llu rays and %llu start shadow rays, %.1f s\n\n",
                reference_run.at("patches").get<unsigned long long>(),
                reference_run.at("rays").get<unsigned long long>(),
                reference_run.at("start_rays").get<unsigned long long>(),
                reference_run.at("wall_seconds").get<double>());
  }
  std::printf("%-16s %7s %6s %7s %9s %8s %7s %7s %11s %8s %8s | %7s %7s %8s\n", "budget", "wall s",
              "mesh s", "start s", "start Mr", "solve s", "disp s", "disp Mr", "rays", "rounds",
              "unshot", "median", "p95", "bias");
  nlohmann::json runs = nlohmann::json::array();
  for (const Budget& budget : budgets) {
    nlohmann::json run = RenderWith(budget, o, root);
    std::printf("%-16s %7.1f %6.1f %7.1f %9.2f %8.1f %7.1f %7.2f %11llu %8llu %7.3f%% |",
                budget.name.c_str(), run.at("wall_seconds").get<double>(),
                run.at("mesh_seconds").get<double>(), run.at("start_seconds").get<double>(),
                run.at("start_rays").get<double>() / 1e6, run.at("solve_seconds").get<double>(),
                run.at("display_seconds").get<double>(), run.at("display_rays").get<double>() / 1e6,
                run.at("rays").get<unsigned long long>(),
                run.at("rounds").get<unsigned long long>(),
                100 * run.at("unshot_fraction").get<double>());
    if (reference) {
      const PatchErrors e =
          Errors(ReadPatches(run.at("patches_csv").get<std::string>()), *reference);
      run.update({{"error_median", e.median}, {"error_p95", e.p95}, {"error_bias", e.bias}});
      std::printf(" %6.2f%% %6.2f%% %+7.3f%%", 100 * e.median, 100 * e.p95, 100 * e.bias);
    }
    std::printf("\n");
    std::fflush(stdout);
    run.erase("patches_csv");
    runs.push_back(std::move(run));
  }
  if (o.reference) reference_run.erase("patches_csv");
  WriteJson(o.json, {{"machine", MachineJson(machine)},
                     {"scene", "scenes/cornell-box.toml"},
                     {"patch_size", o.patch_size},
                     {"threads", 2},
                     {"reference", reference_run},
                     {"runs", runs}});
  std::printf("wrote %s\n", o.json.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  try {
    return radfarm::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "budget_bench: %s\n", e.what());
    return 1;
  }
}
