// illuminance_bench: the illuminance report's lux (output/illuminance_light.h) against the
// path-traced reference (reference/path_tracer.h) at the same grid points.
//
//   illuminance_bench [--max-points N] [--relative-error E] [--max-samples N] [--threads N]
//                     [--seed S] [--work DIR] [--out FILE] [--render-arg ARG]...
//                     [NAME=JOB:HEIGHT:SPACING]...
//
// For each case: JOB copied to WORK/NAME/job.toml with its scene path made absolute and one plane
// added (`[[illuminance]] name = "plane"`, HEIGHT and SPACING in scene units), `radfarm render` of
// it, the points of illuminance/plane.csv (every k-th where there are more than N), the reference
// irradiance there to a relative standard error E, both in lux, and the report's relative error:
// median, p95, worst, mean bias (points darker than 1% of the median reference counted as dark,
// not scored). Prints a table; writes every point's figures as JSON (default
// bench/results/illuminance_bench.json).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "input/scene_loader.h"
#include "job/job.h"
#include "output/illuminance_light.h"
#include "reference/path_tracer.h"
#include "reference/reference_scene.h"

namespace radfarm::reference {
namespace {

struct Case {
  std::string name, job;
  double height = 0, spacing = 0;
};

struct Options {
  size_t max_points = 200;
  TraceSettings trace;
  std::string work = "/tmp/illuminance_bench";
  std::string out = bench::DefaultJsonPath("illuminance_bench");
  std::vector<std::string> render_args;
  std::vector<Case> cases;
};

struct Point {
  Vec3 position;
  double lux = 0;
};

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::string Quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// NAME=JOB:HEIGHT:SPACING
Case ParseCase(const std::string& arg) {
  const size_t eq = arg.find('='), second = arg.rfind(':');
  const size_t first = second == std::string::npos ? second : arg.rfind(':', second - 1);
  if (eq == std::string::npos || first == std::string::npos || first < eq) {
    throw std::runtime_error("a case is NAME=JOB:HEIGHT:SPACING, not " + arg);
  }
  return {arg.substr(0, eq), arg.substr(eq + 1, first - eq - 1),
          std::stod(arg.substr(first + 1, second - first - 1)), std::stod(arg.substr(second + 1))};
}

bool ParseOptions(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: illuminance_bench [--max-points N] [--relative-error E] [--max-samples N]\n"
          "         [--threads N] [--seed S] [--work DIR] [--out FILE] [--render-arg ARG]...\n"
          "         [NAME=JOB:HEIGHT:SPACING]...\n"
          "Renders each job with one illuminance plane, traces the reference irradiance at its\n"
          "grid points and prints the report's error in lux against it (median, p95, worst,\n"
          "bias). Default cases: the Cornell box (mm, its panel) and the Cornell box lit by\n"
          "lamps (metres, candela and a sun). A `radfarm building` job is a case as any other.\n");
      std::exit(0);
    } else if (arg == "--max-points") {
      o->max_points = std::stoul(value());
    } else if (arg == "--relative-error") {
      o->trace.relative_error = std::stod(value());
    } else if (arg == "--max-samples") {
      o->trace.max_samples = std::stoull(value());
      o->trace.min_samples = std::min(o->trace.min_samples, o->trace.max_samples);
    } else if (arg == "--threads") {
      o->trace.threads = unsigned(std::stoul(value()));
    } else if (arg == "--seed") {
      o->trace.seed = std::stoull(value());
    } else if (arg == "--work") {
      o->work = value();
    } else if (arg == "--out") {
      o->out = value();
    } else if (arg == "--render-arg") {
      o->render_args.push_back(value());
    } else if (!arg.empty() && arg[0] == '-') {
      throw std::runtime_error("unknown option " + arg);
    } else {
      o->cases.push_back(ParseCase(arg));
    }
  }
  if (o->cases.empty()) {
    const std::string scenes = RADFARM_SOURCE_DIR "/scenes/";
    o->cases = {{"cornell-box", scenes + "cornell-box.toml", 100, 50},
                {"cornell-box-lamp", scenes + "cornell-box-lamp.toml", 0.1, 0.05}};
  }
  return true;
}

// The case's job with its scene path absolute and the plane appended (a new table at the end).
std::string PlaneJob(const Case& c, const Job& job) {
  std::ifstream in(c.job);
  std::ostringstream text;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("scene", 0) == 0 && line.find('=') != std::string::npos) {
      line = "scene = \"" + std::filesystem::absolute(job.scene_path).string() + "\"";
    }
    text << line << "\n";
  }
  text << "\n[[illuminance]]\nname = \"plane\"\nheight = " << c.height
       << "\nspacing = " << c.spacing << "\n";
  return text.str();
}

std::vector<Point> ReadPlaneCsv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // the header
  std::vector<Point> points;
  while (std::getline(in, line)) {
    Point p;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &p.position.x, &p.position.y, &p.position.z,
                    &p.lux) == 4) {
      points.push_back(p);
    }
  }
  return points;
}

struct Summary {
  double median = 0, p95 = 0, worst = 0, bias = 0, reference_error = 0;
};

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * double(v.size())))];
}

nlohmann::json RunCase(const Options& o, const Case& c) {
  Result<Job> job = LoadJob(c.job);
  if (!job) throw std::runtime_error(job.error());
  Result<InputScene> input = LoadScene(job->scene_path);
  if (!input) throw std::runtime_error(input.error());
  ApplyJobTwoSided(job->two_sided, job->material_two_sided, &*input);
  auto scene = ReferenceScene::Build(*input);
  if (!scene) throw std::runtime_error(scene.error());

  const std::string dir = o.work + "/" + c.name;
  std::filesystem::create_directories(dir);
  const std::string job_path = dir + "/job.toml";
  std::ofstream(job_path) << PlaneJob(c, *job);
  std::string command = Quote(RADFARM_CLI_PATH) + " render " + Quote(job_path) + " --out " +
                        Quote(dir + "/out") + " --threads " + std::to_string(o.trace.threads) +
                        " --quiet";
  for (const std::string& a : o.render_args) command += " " + Quote(a);
  const auto render_start = std::chrono::steady_clock::now();
  if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
  const double render_seconds = Seconds(render_start);

  std::vector<Point> all = ReadPlaneCsv(dir + "/out/illuminance/plane.csv");
  std::vector<Point> points;
  const size_t step =
      std::max<size_t>(1, (all.size() + o.max_points - 1) / std::max<size_t>(1, o.max_points));
  for (size_t i = 0; i < all.size(); i += step) points.push_back(all[i]);
  std::vector<Vec3> positions, normals(points.size(), Vec3{0, 1, 0});
  for (const Point& p : points) positions.push_back(p.position);
  const auto trace_start = std::chrono::steady_clock::now();
  const std::vector<PointEstimate> reference =
      PathTracer(**scene).EstimateIrradianceAll(positions, normals, o.trace);
  const double trace_seconds = Seconds(trace_start);

  // Points darker than 1% of the median reference (in a desk's shadow) have no meaningful
  // relative error: counted as dark, not scored.
  std::vector<double> wanted;
  for (const PointEstimate& e : reference) wanted.push_back(LuxOf(e.radiance));
  const double dark_below = 0.01 * Quantile(wanted, 0.5);
  size_t dark = 0;
  std::vector<double> abs_errors, errors, reference_errors;
  nlohmann::json rows = nlohmann::json::array();
  for (size_t i = 0; i < points.size(); ++i) {
    const double want = wanted[i];
    if (!(want > dark_below)) {
      ++dark;
    } else {
      const double error = points[i].lux / want - 1;
      errors.push_back(error);
      abs_errors.push_back(std::fabs(error));
      reference_errors.push_back(reference[i].relative_error);
    }
    rows.push_back(
        {{"position", {points[i].position.x, points[i].position.y, points[i].position.z}},
         {"lux", points[i].lux},
         {"reference_lux", want},
         {"reference_relative_error", reference[i].relative_error},
         {"samples", reference[i].samples}});
  }
  Summary s;
  s.median = Quantile(abs_errors, 0.5);
  s.p95 = Quantile(abs_errors, 0.95);
  s.worst = abs_errors.empty() ? 0 : *std::max_element(abs_errors.begin(), abs_errors.end());
  for (double e : errors) s.bias += e / double(std::max<size_t>(1, errors.size()));
  s.reference_error = Quantile(reference_errors, 0.5);
  std::printf("%-20s %7zu %6zu %9.2f %9.2f %7.2f%% %7.2f%% %7.2f%% %+7.2f%% %7.2f%% %5zu\n",
              c.name.c_str(), all.size(), points.size(), render_seconds, trace_seconds,
              100 * s.median, 100 * s.p95, 100 * s.worst, 100 * s.bias, 100 * s.reference_error,
              dark);
  return {{"name", c.name},
          {"job", c.job},
          {"height", c.height},
          {"spacing", c.spacing},
          {"plane_points", all.size()},
          {"points", points.size()},
          {"dark_points", dark},
          {"render_wall_seconds", render_seconds},
          {"reference_seconds", trace_seconds},
          {"median_error", s.median},
          {"p95_error", s.p95},
          {"worst_error", s.worst},
          {"mean_bias", s.bias},
          {"reference_median_relative_error", s.reference_error},
          {"rows", rows}};
}

int Main(int argc, char** argv) {
  Options o;
  ParseOptions(argc, argv, &o);
  std::printf("%-20s %7s %6s %9s %9s %8s %8s %8s %8s %8s %5s\n", "case", "plane", "points",
              "render s", "ref s", "median", "p95", "worst", "bias", "ref err", "dark");
  nlohmann::json cases = nlohmann::json::array();
  for (const Case& c : o.cases) cases.push_back(RunCase(o, c));
  bench::WriteJson(o.out, {{"benchmark", "illuminance_bench"},
                           {"trace_relative_error", o.trace.relative_error},
                           {"trace_max_samples", o.trace.max_samples},
                           {"render_args", o.render_args},
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
    std::fprintf(stderr, "illuminance_bench: %s\n", e.what());
    return 2;
  }
}
