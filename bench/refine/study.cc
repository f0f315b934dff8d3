#include "bench/refine/study.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "bench/bench_scene.h"
#include "core/direct_light.h"
#include "display/display_stage.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"
#include "output/png_writer.h"
#include "output/tone_map.h"
#include "solve/local_solve.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

std::string Fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

class Study {
 public:
  Study(const StudyScene& scene, const StudyOptions& options) : options_(options) {
    if (scene.building_rooms > 0) {
      LoadBuilding(scene);
    } else {
      Load(std::string(RADFARM_SOURCE_DIR) + "/scenes/" + scene.name + ".toml");
    }
    camera_ = job_.camera;
    camera_.width = camera_.height = 256;
    result_.scene = scene;
  }

  // The job file and its scene.
  void Load(const std::string& job_path) {
    Result<Job> job = LoadJob(job_path);
    if (!job.ok()) throw std::runtime_error(job.error());
    job_ = std::move(*job);
    Result<InputScene> input = LoadObjScene(job_.scene_path);
    if (!input.ok()) throw std::runtime_error(input.error());
    input_ = std::move(*input);
  }

  // `radfarm building --rooms NxN` written to a temporary directory, loaded, and removed.
  void LoadBuilding(const StudyScene& scene) {
    scenegen::BuildingParams params;
    params.rooms_x = params.rooms_z = scene.building_rooms;
    const testing::TempDir dir("radfarm-refine-bench");
    Load(WriteBuildingJob(params, scene.default_size, dir.path(), scene.name));
  }

  StudyResult Run() {
    const StudyScene& s = result_.scene;
    ref_ = SolveReference(input_, s.name, s.reference_size, s.reference_shot_rays, camera_,
                          options_.reference_cache);
    result_.reference_patches = ref_.scene.patches.size();
    result_.reference_rays = ref_.rays;
    result_.reference_seconds = ref_.seconds;
    std::printf("%s reference: %zu patches, %llu rays, %.1f s\n", s.name.c_str(),
                ref_.scene.patches.size(), (unsigned long long)ref_.rays, ref_.seconds);

    // A job's defaults: sobol, tolerance 1e-3, automatic shot_rays, seed 1, final gather of
    // kDefaultGatherRays (refining rows shoot without it: RefinementSchedule::SolverSettingsNow).
    const SolverSettings defaults = Job{}.solver;
    const RefineSettings off;
    for (double size : s.uniform_sizes) {
      Measure("uniform", "uniform", "patch size " + Fmt(size), size, defaults, off);
    }
    // The reference's own patches, solved like every other row: the least error a mesh can show
    // at these rays, since the reference shares its discretisation and only the noise is left.
    Measure("floor", "the reference's mesh", "patch size " + Fmt(s.reference_size),
            s.reference_size, defaults, off);
    for (double start : s.adaptive_starts) {
      for (double tolerance : s.tolerances) {
        RefineSettings on;
        on.enabled = true;
        on.tolerance = tolerance;
        // A little under the reference's size: a start of twice that size has patches a little
        // smaller than twice it, and an element splits only if its children keep the minimum.
        on.min_element_size = 0.9 * s.reference_size;
        Measure("adaptive", "adaptive", "start " + Fmt(start) + ", tolerance " + Fmt(tolerance),
                start, defaults, on);
      }
    }
    if (!s.compare_settings) return std::move(result_);
    // Copies: Measure() appends rows, which may move them.
    const Row* sobol = UniformAt(s.default_size);
    if (sobol == nullptr) throw std::runtime_error(s.name + ": no uniform row at the default size");
    const uint64_t sobol_rays = sobol->rays;
    const uint64_t default_patches = sobol->patches;
    SolverSettings random = defaults;
    random.sampler = SamplerKind::kRandom;
    Measure("sampler", "random", "patch size " + Fmt(s.default_size), s.default_size, random, off);
    SolverSettings grid = defaults;
    grid.sampler = SamplerKind::kGrid;
    grid.grid_step_degrees = 4;
    grid.shooters_per_round = 16;
    grid.max_rays = 4 * sobol_rays;  // the grid converges slowly: stop it at 4x Sobol's rays
    Measure("sampler", "grid 4°, 16 shooters per round",
            "patch size " + Fmt(s.default_size) + ", at most 4x the Sobol rays", s.default_size,
            grid, off);
    SolverSettings seed = defaults;
    seed.sampler = SamplerKind::kGrid;
    seed.grid_step_degrees = 1;
    seed.shooters_per_round = 1;
    seed.max_rays = 20 * 90 * 360;
    Measure("sampler", "seed method (baseline)",
            "grid 1°, 20 shots, patch size " + Fmt(s.default_size), s.default_size, seed, off);
    // Progressive refinement with over-relaxation (plain Southwell is the uniform row above).
    // Capped at 4x the plain rows' rays: from about 1.5 the Monte Carlo overshoot can diverge.
    for (double omega : options_.quick ? std::vector<double>{1.2} : std::vector<double>{1.1, 1.3}) {
      SolverSettings over = defaults;
      over.overrelaxation = omega;
      over.max_rays = 4 * sobol_rays;
      Measure("solver", "over-relaxation " + Fmt(omega),
              "patch size " + Fmt(s.default_size) + ", at most 4x the plain rays", s.default_size,
              over, off);
    }
    // Plain progressive refinement: no final gather, the automatic rays of a shooting solve.
    SolverSettings shooting = defaults;
    shooting.gather_rays = 0;
    Measure("gather", "no final gather", "patch size " + Fmt(s.default_size), s.default_size,
            shooting, off);
    // The default settings with more rays per patch, shooting and gathering.
    for (uint64_t factor : options_.quick ? std::vector<uint64_t>{} : std::vector<uint64_t>{4}) {
      SolverSettings more = defaults;
      more.shot_rays = factor * ResolvedShotRays(defaults, default_patches);
      more.gather_rays = static_cast<uint32_t>(factor * defaults.gather_rays);
      Measure("budget", "default, " + Fmt(double(factor)) + "x rays",
              "patch size " + Fmt(s.default_size) + ", shot_rays " +
                  std::to_string(more.shot_rays) + ", gather_rays " +
                  std::to_string(more.gather_rays),
              s.default_size, more, off);
    }
    return std::move(result_);
  }

 private:
  const Row* UniformAt(double size) const {
    for (const Row& r : result_.rows) {
      if (r.group == "uniform" && r.start_size == size) return &r;
    }
    return nullptr;
  }

  void Measure(const std::string& group, const std::string& method, const std::string& setting,
               double patch_size, const SolverSettings& solver, const RefineSettings& refine) {
    // The median of a few runs' times (a shared machine's load comes and goes); the runs are
    // bit-identical, so the last one's solution stands for all.
    const int repeats = TimedRuns(options_);
    std::vector<double> times;
    Result<RefiningSolveResult> solved = Error{"not run"};
    for (int run = 0; run < repeats; ++run) {
      Result<PatchMesh> mesh = PatchMesh::Build(input_, {patch_size}, nullptr);
      if (!mesh.ok()) throw std::runtime_error(mesh.error());
      const auto start = std::chrono::steady_clock::now();
      solved = SolveRefining(std::move(*mesh), solver, refine);
      times.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      if (!solved.ok()) throw std::runtime_error(solved.error());
    }
    std::sort(times.begin(), times.end());
    const double seconds = times[times.size() / 2];
    Row row;
    row.group = group;
    row.method = method;
    row.setting = setting;
    row.start_size = patch_size;
    row.refine_tolerance = refine.enabled ? refine.tolerance : 0;
    row.patches_before = solved->patches_before;
    row.patches = solved->mesh->patch_scene().patches.size();
    row.rays = solved->solution.stats.rays;
    row.seconds = seconds;
    row.patch_error =
        MeasurePatchError(solved->mesh->patch_scene(), solved->solution.radiosity, ref_);
    // As `radfarm render` shades it (cli/render_outputs.cc).
    const auto display_start = std::chrono::steady_clock::now();
    const PatchMesh& mesh = *solved->mesh;
    const DisplayTopology topology = mesh.display_topology();
    const DisplayMesh display =
        solved->solution.direct_light.empty()
            ? AveragedDisplay(topology, mesh.patch_scene(), solved->solution.radiosity)
            : ShadeDisplay(
                  {topology, mesh.patch_scene(), mesh.patch_size(), solved->solution.radiosity,
                   solved->solution.direct_light},
                  {solver.seed, solver.threads, EmittersInDirectStart(mesh.patch_scene(), solver),
                   DirectLightRaysPerLight(mesh.patch_scene(), solver)})
                  .mesh;
    row.display_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - display_start).count();
    const Camera camera = ResolveCamera(display, camera_);
    const Image image = RenderImage(display, camera);
    row.image_error = MeasureImageError(image, ref_);
    if (!solved->solution.direct_light.empty()) {
      const ImagePartErrors parts =
          MeasureImagePartErrors(*solved->mesh, solved->solution, solver, camera, ref_);
      row.direct_image_error = parts.direct;
      row.bounced_image_error = parts.bounced;
      // The mesh's display is the measures' now: unused after this.
      row.display_image_error =
          MeasureDisplayError(*solved->mesh, solved->solution, solver, camera, ref_);
    }
    if (!options_.images_dir.empty()) {
      // Debugging aid: the row's image and its difference from the reference, 8x brightened.
      const std::string stem = options_.images_dir + "/" + result_.scene.name + "-" +
                               std::to_string(result_.rows.size());
      Camera fixed = camera;
      fixed.auto_exposure = false;
      fixed.exposure = AutoExposureStops(ref_.image);
      (void)WritePng(stem + ".png", image, fixed);
      Image diff = image;
      for (size_t i = 0; i < diff.pixels.size(); ++i) {
        const double d = image.pixels[i].Sum() - ref_.image.pixels[i].Sum();
        diff.pixels[i] = d > 0 ? Rgb{8 * d, 0, 0} : Rgb{0, 0, -8 * d};
      }
      (void)WritePng(stem + "-diff.png", diff, fixed);
    }
    std::printf(
        "%-14s %-26s %-36s %6llu -> %6llu patches %10llu rays %7.2f s  patch %.4f (ref "
        "%.4f, net %.4f)  image %.4f\n",
        result_.scene.name.c_str(), method.c_str(), setting.c_str(),
        (unsigned long long)row.patches_before, (unsigned long long)row.patches,
        (unsigned long long)row.rays, row.seconds, row.patch_error.measured,
        row.patch_error.reference_noise, row.patch_error.net, row.image_error);
    std::fflush(stdout);
    result_.rows.push_back(std::move(row));
  }

  StudyOptions options_;
  Job job_;
  InputScene input_;
  Camera camera_;
  ReferenceSolution ref_;
  StudyResult result_;
};

}  // namespace

std::vector<StudyScene> StudyScenes(bool quick) {
  if (quick) {
    return {{"cornell-box", 25, 25, 1u << 20, {100, 50, 25}, {100}, {0.1}},
            {"hard-shadow", 0.25, 0.125, 1u << 20, {0.5, 0.25}, {0.5}, {0.1}}};
  }
  // Uniform meshes down to about 1.3x the reference's size (the reference's own mesh would match
  // it too well); adaptive runs start at the default size and twice it, down to the reference's.
  return {
      {"cornell-box",
       25,
       12.5,
       1u << 26,
       {100, 50, 33.3, 25, 16.7},
       {50, 25},
       {0.1, 0.05, 0.02, 0.01, 0.005}},
      {"seed-room",
       0.5,
       0.125,
       1u << 25,
       {1, 0.5, 0.25, 0.1667},
       {1, 0.5},
       {0.1, 0.05, 0.02, 0.01, 0.005}},
      {"hard-shadow",
       0.25,
       0.0625,
       1u << 25,
       {0.5, 0.25, 0.125, 0.0833},
       {0.25, 0.125},
       {0.1, 0.05, 0.02, 0.01, 0.005}},
      // An office floor (2 x 2 rooms, furniture, 8 ceiling panels): contact shadows
      // under desks and chairs, penumbrae of panels 1 cm below the ceiling. Meshes and refinement
      // only: the samplers and budgets compare alike on the rooms above.
      {"building-2x2",
       0.25,
       0.125,
       1u << 25,
       {1, 0.5, 0.25, 0.1667},
       {0.5, 0.25},
       {0.1, 0.05, 0.02, 0.01, 0.005},
       2,
       false},
  };
}

int TimedRuns(const StudyOptions& options) { return options.quick ? 1 : 3; }

StudyResult RunStudy(const StudyScene& scene, const StudyOptions& options) {
  return Study(scene, options).Run();
}

}  // namespace radfarm::bench
