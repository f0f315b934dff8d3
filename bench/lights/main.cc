// light_bench: does a point's direct light still cost the same with 10^4 lights? On the
// procedural building with 10, 100, 1000 and 10^4 ceiling panels, two per room in more rooms and
// floors, or all in one open-plan room (`--lights AxB`), the direct light at area-uniform points of
// its surfaces through the light tree (DirectLight above kExactLights lights, core/light_tree.h)
// against the exact sum over every light with the same shadow rays: time per point on one thread,
// lights evaluated per point, and the relative error per point. Prints a table and writes
// bench/results/light_bench.json.
//
//   light_bench [--points N] [--quick] [--only LIGHTS] [--json PATH]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/bench_scene.h"
#include "bench/machine_info.h"
#include "bench/stopwatch.h"
#include "core/counter_rng.h"
#include "core/direct_light.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"

namespace radfarm::bench {
namespace {

// The building's meshing: coarse, so that 5000 rooms stay a few hundred thousand patches.
constexpr double kPatchSize = 1.0;

struct Options {
  uint32_t points = 1000;
  bool quick = false;
  int only = 0;  // lights: one case alone
  std::string json = DefaultJsonPath("light_bench");
};

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--points") {
      o.points = uint32_t(std::stoul(next()));
    } else if (a == "--only") {
      o.only = std::stoi(next());
    } else if (a == "--quick") {
      o.quick = true;
    } else if (a == "--json") {
      o.json = next();
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "light_bench [--points N] [--quick] [--only LIGHTS] [--json PATH]\n"
          "  The direct light through the light tree against the exact sum over every light,\n"
          "  on the building with 10, 100, 1000 and 10^4 ceiling lights, in rooms of two or in "
          "one\n"
          "  open-plan room (--quick: up to 1000),\n"
          "  at N points (1000); --only 1000: that case alone. Writes "
          "bench/results/light_bench.json unless --json says "
          "where.\n");
      std::exit(0);
    } else {
      throw std::runtime_error("unknown argument " + a + " (see --help)");
    }
  }
  return o;
}

struct Case {
  const char* layout;  // "rooms": two panels a 4 x 4 m room; "open": one room, a grid of panels
  int lights, floors, rooms_x, rooms_z;
  double room_size = 4;
  int lights_x = 2, lights_z = 1;
};

// Area-uniform points over the non-emitting patches; point i a pure function of (scene, i).
std::vector<ReceiverPoint> SurfacePoints(const PatchScene& scene, double offset, uint32_t count) {
  std::vector<double> cdf;
  std::vector<uint32_t> ids;
  double total = 0;
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    if (scene.patches[i].emission.Max() > 0) continue;
    total += scene.patches[i].area;
    cdf.push_back(total);
    ids.push_back(i);
  }
  std::vector<ReceiverPoint> points;
  for (uint32_t i = 0; i < count; ++i) {
    const CounterRng rng(HashWords(0x6c62656e6368ull, i));
    const size_t at = std::min<size_t>(
        cdf.size() - 1,
        std::upper_bound(cdf.begin(), cdf.end(), rng.Uniform(0) * total) - cdf.begin());
    const Patch& p = scene.patches[ids[at]];
    const PatchSampling sampling = PreparePatchSampling(p, offset);
    points.push_back({SamplePatchPoint(p, sampling, rng.Uniform(1), rng.Uniform(2)), p.normal});
  }
  return points;
}

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * double(v.size())))];
}

// The tree's cut sizes measured: the default and either side of it.
constexpr uint32_t kCuts[] = {kLightCut / 2, kLightCut, kLightCut * 2};

// One cut size against the exact sums `want` at the same points and keys.
nlohmann::json MeasureCut(const PatchScene& patches, const RayCaster& caster,
                          const std::vector<ReceiverPoint>& points, const std::vector<double>& want,
                          uint32_t cut) {
  const DirectLight tree(patches, caster, kPointShadowRays, true, kExactLights, cut);
  std::vector<double> got(points.size());
  uint64_t evaluated_sum = 0;
  uint32_t evaluated_max = 0;
  const Stopwatch clock;
  for (size_t i = 0; i < points.size(); ++i) {
    uint32_t evaluated = 0;
    got[i] =
        tree.EmitterIrradiance(points[i].position, points[i].normal, HashWords(7, i), &evaluated)
            .Sum();
    evaluated_sum += evaluated;
    evaluated_max = std::max(evaluated_max, evaluated);
  }
  const double seconds = clock.Seconds();
  std::vector<double> relative;
  double want_total = 0, got_total = 0;
  uint32_t dark_lit = 0;  // no light in the exact sum, some in the tree's: must stay 0
  for (size_t i = 0; i < points.size(); ++i) {
    want_total += want[i];
    got_total += got[i];
    if (want[i] > 0) {
      relative.push_back(std::fabs(got[i] / want[i] - 1));
    } else {
      dark_lit += got[i] != 0;
    }
  }
  const double n = double(points.size());
  return {{"cut", cut},
          {"sampled", tree.emitters_sampled()},
          {"us_per_point", 1e6 * seconds / n},
          {"lights_per_point", double(evaluated_sum) / n},
          {"lights_per_point_max", evaluated_max},
          {"dark_points_lit", dark_lit},
          {"median_relative_error", relative.empty() ? 0.0 : Median(relative)},
          {"p95_relative_error", Quantile(relative, 0.95)},
          {"max_relative_error", Quantile(relative, 1.0)},
          {"mean_bias", want_total > 0 ? got_total / want_total - 1 : 0.0}};
}

nlohmann::json RunCase(const Case& c, uint32_t count) {
  scenegen::BuildingParams params;
  params.floors = c.floors;
  params.rooms_x = c.rooms_x;
  params.rooms_z = c.rooms_z;
  params.room_width = params.room_depth = c.room_size;
  params.lights_x = c.lights_x;
  params.lights_z = c.lights_z;
  const std::string name = std::string("building-") + c.layout + "-" + std::to_string(c.lights);
  const BenchScene scene = LoadBuildingBenchScene(name, params, kPatchSize);
  const PatchScene& patches = scene.patches();
  const RayCaster caster(patches);
  const Stopwatch build;
  const DirectLight with_tree(patches, caster, kPointShadowRays);
  const double build_seconds = build.Seconds();
  const DirectLight exact(patches, caster, kPointShadowRays, true,
                          std::numeric_limits<size_t>::max());
  const std::vector<ReceiverPoint> points = SurfacePoints(patches, caster.origin_offset(), count);

  // One thread; the exact sum at every point, then each cut with the same keys.
  std::vector<double> want(points.size());
  const Stopwatch clock;
  for (size_t i = 0; i < points.size(); ++i) {
    want[i] = exact.EmitterIrradiance(points[i].position, points[i].normal, HashWords(7, i)).Sum();
  }
  const double exact_us = 1e6 * clock.Seconds() / double(points.size());
  const auto lit = std::count_if(want.begin(), want.end(), [](double w) { return w > 0; });
  std::printf("%s: %zu lights, %zu patches, %zu points (%td lit); exact sum %.1f us/point\n",
              scene.path.c_str(), exact.emitter_lights(), patches.patches.size(), points.size(),
              lit, exact_us);
  nlohmann::json cuts = nlohmann::json::array();
  for (const uint32_t cut : kCuts) {
    const nlohmann::json m = MeasureCut(patches, caster, points, want, cut);
    std::printf(
        "  cut %3u: %7.1f us/point, %5.1f lights/point (max %u); relative error median "
        "%.2g%%, p95 %.2g%%, max %.2g%%; bias %+.2g%%%s\n",
        cut, m["us_per_point"].get<double>(), m["lights_per_point"].get<double>(),
        m["lights_per_point_max"].get<uint32_t>(), 100 * m["median_relative_error"].get<double>(),
        100 * m["p95_relative_error"].get<double>(), 100 * m["max_relative_error"].get<double>(),
        100 * m["mean_bias"].get<double>(), m["sampled"].get<bool>() ? "" : " (exact: few lights)");
    std::fflush(stdout);
    cuts.push_back(m);
  }
  return {{"layout", c.layout},
          {"scene", scene.path},
          {"lights", exact.emitter_lights()},
          {"patches", patches.patches.size()},
          {"points", points.size()},
          {"lit_points", lit},
          {"load_seconds", scene.load_seconds},
          {"tree_build_seconds", build_seconds},
          {"exact_us_per_point", exact_us},
          {"cuts", cuts}};
}

int Main(int argc, char** argv) {
  const Options o = Parse(argc, argv);
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  const Stopwatch total;
  // Two panels per room: 5, 50, 500 and 5000 rooms.
  const std::vector<Case> cases = {{"rooms", 10, 1, 5, 1},
                                   {"rooms", 100, 1, 10, 5},
                                   {"rooms", 1000, 2, 25, 10},
                                   {"rooms", 10000, 10, 25, 20},
                                   {"open", 10, 1, 1, 1, 10, 5, 2},
                                   {"open", 100, 1, 1, 1, 20, 10, 10},
                                   {"open", 1000, 1, 1, 1, 40, 40, 25},
                                   {"open", 10000, 1, 1, 1, 50, 100, 100}};
  nlohmann::json runs = nlohmann::json::array();
  for (const Case& c : cases) {
    if (o.quick && c.lights > 1000) continue;
    if (o.only != 0 && o.only != c.lights) continue;
    runs.push_back(RunCase(c, o.points));
  }
  nlohmann::json out{{"machine", MachineJson(machine)},
                     {"patch_size", kPatchSize},
                     {"exact_lights", kExactLights},
                     {"light_cut", kLightCut},
                     {"threads", 1},
                     {"quick", o.quick},
                     {"runs", runs},
                     {"total_seconds", total.Seconds()}};
  out["load_average_end"] = ReadLoadAverage();
  WriteJson(o.json, out);
  std::printf("wrote %s\n", o.json.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  try {
    return radfarm::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "light_bench: %s\n", e.what());
    return 1;
  }
}
