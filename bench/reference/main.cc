// reference_bench: the display's error against the path-traced reference (reference/) on
// scenes rendered by `radfarm render`, with the render's time beside it.
//
//   reference_bench [--points N] [--band-points N] [--band-patches W] [--seed S] [--relative-error
//   E] [--max-samples N] [--threads N]
//                   [--work DIR] [--out FILE] [--render-arg ARG]... [--reference-from FILE]
//                   [NAME=JOB]...
//
// For each case: `radfarm render JOB --out WORK/NAME --threads T` (timed), the display read back
// from radiosity.ply, N area-uniform points of the input's surfaces, the reference there to a
// relative standard error E, and the display's relative error: median, p95, worst, mean bias; then
// the same on N points area-uniform over the band within W patch sizes of another surface
// (contact lines, corners, the slit above a hanging lamp), where a display's errors gather, and
// the band split by how each point's surface meets the nearest (shared edge, junction, gap), and
// a kind whose faces there include one narrower than a patch (a leg) split again, narrow and wide.
// Prints a table; writes every point's figures as JSON (default
// bench/results/reference_bench.json). With --reference-from, a case whose points are those of the
// same case in that earlier JSON takes their reference from it instead of tracing again: the
// display of a changed solver is scored against the very reference its predecessor was.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "input/scene_loader.h"
#include "job/job.h"
#include "reference/band_contact.h"
#include "reference/display_error.h"
#include "reference/display_lookup.h"
#include "reference/path_tracer.h"
#include "reference/reference_scene.h"
#include "reference/surface_points.h"

namespace radfarm::reference {
namespace {

struct Options {
  uint32_t points = 300;
  uint32_t band_points = 300;  // near another surface (SampleBandPoints)
  double band_patches = 1.5;   // the band's width in patch sizes
  uint64_t seed = 1;
  TraceSettings trace;
  std::string work = "/tmp/reference_bench";
  std::string out = bench::DefaultJsonPath("reference_bench");
  std::vector<std::string> render_args;
  std::vector<std::pair<std::string, std::string>> cases;  // name, job
  nlohmann::json reference_from;                           // an earlier run's JSON, or null
};

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

nlohmann::json RgbJson(const Rgb& c) { return {c.r, c.g, c.b}; }
nlohmann::json VecJson(const Vec3& v) { return {v.x, v.y, v.z}; }

bool ParseOptions(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: reference_bench [--points N] [--band-points N] [--band-patches W] [--seed S]\n"
          "         [--relative-error E] [--max-samples N] [--threads N] [--work DIR] [--out "
          "FILE]\n"
          "         [--render-arg ARG]... [--reference-from FILE] [NAME=JOB]...\n"
          "Renders each job, traces an unbiased reference at area-uniform points and at points\n"
          "near other surfaces, and prints the display's error against it (median, p95, worst,\n"
          "bias). --reference-from reuses the reference of an earlier run's JSON where its\n"
          "points are the same. Default cases: the Cornell box, lamp-under-ceiling,\n"
          "block-on-floor.\n");
      std::exit(0);
    }
    if (arg == "--points")
      o->points = uint32_t(std::stoul(value()));
    else if (arg == "--band-points")
      o->band_points = uint32_t(std::stoul(value()));
    else if (arg == "--band-patches")
      o->band_patches = std::stod(value());
    else if (arg == "--seed")
      o->seed = o->trace.seed = std::stoull(value());
    else if (arg == "--relative-error")
      o->trace.relative_error = std::stod(value());
    else if (arg == "--max-samples")
      o->trace.max_samples = std::stoull(value());
    else if (arg == "--threads")
      o->trace.threads = unsigned(std::stoul(value()));
    else if (arg == "--work")
      o->work = value();
    else if (arg == "--out")
      o->out = value();
    else if (arg == "--reference-from") {
      const std::string path = value();
      std::ifstream in(path);
      if (!in) throw std::runtime_error("--reference-from: cannot read " + path);
      o->reference_from = nlohmann::json::parse(in);
    } else if (arg == "--render-arg")
      o->render_args.push_back(value());
    else if (arg.find('=') != std::string::npos && arg[0] != '-') {
      o->cases.emplace_back(arg.substr(0, arg.find('=')), arg.substr(arg.find('=') + 1));
    } else {
      std::fprintf(stderr, "reference_bench: unknown argument '%s'\n", arg.c_str());
      return false;
    }
  }
  if (o->cases.empty()) {
    const std::string scenes = std::string(RADFARM_SOURCE_DIR) + "/scenes/";
    o->cases = {{"cornell-box", scenes + "cornell-box.toml"},
                {"lamp-under-ceiling", scenes + "lamp-under-ceiling.toml"},
                {"block-on-floor", scenes + "block-on-floor.toml"}};
  }
  return true;
}

std::string Quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The earlier run's reference at `points`, when that run's case `name` has set `set` at the same
// points (to a millionth of the scene's diagonal); empty otherwise.
std::vector<PointEstimate> EarlierReference(const Options& o, const std::string& name,
                                            const std::string& set,
                                            const std::vector<SurfacePoint>& points,
                                            double tolerance) {
  if (o.reference_from.is_null()) return {};
  for (const nlohmann::json& c : o.reference_from.value("cases", nlohmann::json::array())) {
    if (c.value("name", "") != name || !c.contains("sets") || !c["sets"].contains(set)) continue;
    const nlohmann::json& raw = c["sets"][set]["points"];
    if (raw.size() != points.size()) return {};
    std::vector<PointEstimate> out;
    for (size_t i = 0; i < points.size(); ++i) {
      const nlohmann::json& p = raw[i];
      const Vec3 at{p["position"][0], p["position"][1], p["position"][2]};
      if (Length(at - points[i].position) > tolerance) return {};
      auto rgb = [](const nlohmann::json& v) { return Rgb(v[0], v[1], v[2]); };
      out.push_back({rgb(p["reference"]), rgb(p["reference_standard_error"]),
                     p["reference_relative_error"], p["samples"], 0});
    }
    return out;
  }
  return {};
}

nlohmann::json SummaryJson(const ErrorSummary& s) {
  return {{"points", s.points},
          {"scored", s.scored},
          {"dark", s.dark},
          {"unfound", s.unfound},
          {"median", s.median},
          {"p95", s.p95},
          {"worst", s.worst},
          {"worst_point", s.worst_point},
          {"mean_bias", s.mean_bias},
          {"reference_median_error", s.reference_median_error},
          {"reference_p95_error", s.reference_p95_error}};
}

void PrintSummary(const std::string& name, const std::string& set, long long patches,
                  double render_seconds, double seconds, const ErrorSummary& s) {
  std::printf("%-20s %-11s %8lld %8.2f %8.2f %7.2f%% %7.2f%% %7.2f%% %+7.2f%% %7.2f%% %5u %5u\n",
              name.c_str(), set.c_str(), patches, render_seconds, seconds, 100 * s.median,
              100 * s.p95, 100 * s.worst, 100 * s.mean_bias, 100 * s.reference_median_error, s.dark,
              s.unfound);
}

nlohmann::json RunCase(const Options& o, const std::string& name, const std::string& job_path) {
  Result<Job> job = LoadJob(job_path);
  if (!job) throw std::runtime_error(job.error());
  Result<InputScene> input = LoadScene(job->scene_path);
  if (!input) throw std::runtime_error(input.error());
  ApplyJobTwoSided(job->two_sided, job->material_two_sided, &*input);
  auto scene = ReferenceScene::Build(*input);
  if (!scene) throw std::runtime_error(scene.error());

  const std::string dir = o.work + "/" + name;
  std::filesystem::create_directories(dir);
  std::string command = Quote(RADFARM_CLI_PATH) + " render " + Quote(job_path) + " --out " +
                        Quote(dir) + " --threads " + std::to_string(o.trace.threads) + " --quiet";
  for (const std::string& a : o.render_args) command += " " + Quote(a);
  const auto render_start = std::chrono::steady_clock::now();
  if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
  const double render_seconds = Seconds(render_start);
  nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir + "/stats.json"));

  Result<DisplayPly> ply = ReadDisplayPly(dir + "/radiosity.ply");
  if (!ply) throw std::runtime_error(ply.error());
  const DisplayLookup display(std::move(*ply), (*scene)->diagonal() * 1e-4);
  // The band near other surfaces: band_patches patch sizes wide (2.5% of the scene's diagonal
  // when the job leaves the patch size automatic).
  const double band = job->mesh.patch_size > 0 ? o.band_patches * job->mesh.patch_size
                                               : 0.025 * (*scene)->diagonal();
  const ContactClassifier classifier(**scene, *input);
  nlohmann::json sets = nlohmann::json::object();
  double trace_seconds = 0;
  const std::pair<const char*, std::vector<SurfacePoint>> point_sets[] = {
      {"uniform", SampleSurfacePoints(**scene, o.points, o.seed)},
      {"band", SampleBandPoints(**scene, o.band_points, o.seed, band)}};
  for (const auto& [set, points] : point_sets) {
    const auto trace_start = std::chrono::steady_clock::now();
    std::vector<PointEstimate> refs =
        EarlierReference(o, name, set, points, (*scene)->diagonal() * 1e-6);
    const bool reused = !refs.empty();
    if (!reused) refs = PathTracer(**scene).EstimateAll(points, o.trace);
    const double seconds = Seconds(trace_start);
    trace_seconds += seconds;
    std::vector<PointScore> scores;
    uint64_t samples = 0, rays = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      scores.push_back(
          {points[i], refs[i], display.RadianceAt(points[i].position, points[i].normal)});
      samples += refs[i].samples;
      rays += refs[i].rays;
    }
    const ErrorSummary s = ScoreDisplay(&scores);
    const long long patches = stats.value("patches", 0);
    PrintSummary(name, set, patches, render_seconds, seconds, s);
    if (s.worst_point >= 0) {
      const PointScore& w = scores[size_t(s.worst_point)];
      std::printf("%29s worst at (%g, %g, %g) facing (%g, %g, %g): reference %g, display %g\n", "",
                  w.point.position.x, w.point.position.y, w.point.position.z, w.point.normal.x,
                  w.point.normal.y, w.point.normal.z, w.reference.radiance.Sum(), w.display->Sum());
    }
    // The band's points by how their surface meets the nearest one (band_contact.h), and those
    // kinds with faces narrower than a patch (a table's leg) apart from the rest.
    std::vector<BandContact> contact;
    for (const PointScore& p : scores) contact.push_back(classifier.Classify(p.point, band));
    const double patch = band / o.band_patches;
    nlohmann::json contacts = nlohmann::json::object();
    if (std::string(set) == "band") {
      auto summarize = [&](const std::string& label, auto&& in) {
        std::vector<bool> keep;
        for (const BandContact& pc : contact) keep.push_back(in(pc));
        const ErrorSummary cs = SummarizeScores(scores, keep);
        PrintSummary(name, "  " + label, patches, render_seconds, seconds, cs);
        return SummaryJson(cs);
      };
      for (Contact c : kContacts) {
        const std::string kind = ContactName(c);
        auto narrow = [&](const BandContact& pc) { return pc.kind == c && pc.width < patch; };
        auto wide = [&](const BandContact& pc) { return pc.kind == c && pc.width >= patch; };
        contacts[kind] = summarize(kind, [&](const BandContact& pc) { return pc.kind == c; });
        if (std::none_of(contact.begin(), contact.end(), narrow)) continue;
        contacts[kind + "_narrow"] = summarize(kind + " narrow", narrow);
        contacts[kind + "_wide"] = summarize(kind + " wide", wide);
      }
    }
    std::fflush(stdout);
    nlohmann::json raw = nlohmann::json::array();
    for (size_t i = 0; i < scores.size(); ++i) {
      const PointScore& p = scores[i];
      const uint32_t material = (*scene)->triangles()[p.point.triangle].material;
      raw.push_back({{"position", VecJson(p.point.position)},
                     {"normal", VecJson(p.point.normal)},
                     {"material", input->materials[material].name},
                     {"reference", RgbJson(p.reference.radiance)},
                     {"reference_standard_error", RgbJson(p.reference.standard_error)},
                     {"reference_relative_error", p.reference.relative_error},
                     {"samples", p.reference.samples},
                     {"display", p.display ? RgbJson(*p.display) : nlohmann::json()},
                     {"relative_error", p.relative_error},
                     {"dark", p.dark},
                     {"contact", ContactName(contact[i].kind)},
                     {"contact_width", contact[i].width}});
    }
    sets[set] = {{"reference_seconds", seconds},
                 {"reference_reused", reused},
                 {"reference_samples", samples},
                 {"reference_rays", rays},
                 {"summary", SummaryJson(s)},
                 {"contacts", contacts},
                 {"points", raw}};
  }
  return {{"name", name},
          {"job", job_path},
          {"render_args", o.render_args},
          {"render_wall_seconds", render_seconds},
          {"render_stats", stats},
          {"reference_seconds", trace_seconds},
          {"triangles", (*scene)->triangles().size()},
          {"band", band},
          {"sets", sets}};
}

int Main(int argc, char** argv) {
  Options o;
  if (!ParseOptions(argc, argv, &o)) return 2;
  const bench::MachineInfo machine = bench::ReadMachineInfo(argc, argv);
  std::printf("%-20s %-11s %8s %8s %8s %8s %8s %8s %8s %8s %5s %5s\n", "scene", "points", "patches",
              "render s", "ref s", "median", "p95", "worst", "bias", "ref err", "dark", "miss");
  nlohmann::json cases = nlohmann::json::array();
  const auto start = std::chrono::steady_clock::now();
  for (const auto& [name, job] : o.cases) cases.push_back(RunCase(o, name, job));
  bench::WriteJson(o.out, {{"machine", bench::MachineJson(machine)},
                           {"points", o.points},
                           {"band_points", o.band_points},
                           {"band_patches", o.band_patches},
                           {"seed", o.seed},
                           {"relative_error", o.trace.relative_error},
                           {"max_samples", o.trace.max_samples},
                           {"threads", o.trace.threads},
                           {"load_average_end", bench::ReadLoadAverage()},
                           {"total_seconds", Seconds(start)},
                           {"cases", cases}});
  std::printf("wrote %s\n", o.out.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::reference

int main(int argc, char** argv) {
  try {
    return radfarm::reference::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reference_bench: %s\n", e.what());
    return 1;
  }
}
