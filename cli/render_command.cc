#include "cli/render_command.h"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <system_error>

#include "cli/exit_codes.h"
#include "cli/progress_reporter.h"
#include "core/solve.h"
#include "input/input_scene.h"
#include "input/job.h"
#include "mesh/patch_mesh.h"
#include "output/exposure_meter.h"
#include "output/exr_writer.h"
#include "output/image.h"
#include "output/patches_csv.h"
#include "output/ply_writer.h"
#include "output/png_writer.h"
#include "output/stats_json.h"

namespace radfarm {
namespace {

void PrintError(const std::string& message) {
  std::fprintf(stderr, "radfarm: %s\n", message.c_str());
}

void PrintWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::fprintf(stderr, "radfarm: %s\n", w.c_str());
}

// Applies the command line's overrides on top of the job file's settings.
Status ApplyOverrides(const RenderOptions& options, Job* job) {
  SolverSettings& s = job->solver;
  if (options.threads) s.threads = *options.threads;
  if (options.seed) s.seed = *options.seed;
  if (options.tolerance) s.tolerance = *options.tolerance;
  if (options.rays) s.max_rays = *options.rays;
  if (options.seconds) s.max_seconds = *options.seconds;
  if (options.patch_size) job->mesh.patch_size = *options.patch_size;
  if (options.sampler && !ParseSamplerName(*options.sampler, &s.sampler)) {
    return Error{"--sampler: unknown sampler '" + *options.sampler +
                 "' (expected grid, random or sobol)"};
  }
  return Ok{};
}

Status WriteOutputs(const std::string& dir, PatchMesh& mesh, const SolveResult& solution,
                    const Job& job) {
  namespace fs = std::filesystem;
  mesh.SetSolution(solution.radiosity, solution.unshot);
  const DisplayMesh display = mesh.MakeDisplayMesh();
  std::vector<bool> emitter_patch;
  for (const Patch& p : mesh.patch_scene().patches) emitter_patch.push_back(p.emission.Max() > 0);
  // One exposure, metered on the lit surfaces, for the PNG and the PLY's colours.
  const Camera exposed = MeterExposure(display, emitter_patch, ResolveCamera(display, job.camera));
  const Image image = RenderImage(display, exposed);
  const auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
  for (const Status& s :
       {WritePng(path("image.png"), image, exposed), WriteExr(path("image.exr"), image),
        WritePly(path("radiosity.ply"), display, exposed),
        WritePatchesCsv(path("patches.csv"), mesh.patch_scene(), solution.radiosity),
        WriteStatsJson(path("stats.json"), solution.stats,
                       {{"patch_size", mesh.patch_size()},
                        {"dropped_degenerate_faces", double(mesh.dropped_degenerate())},
                        {"dropped_hidden_faces", double(mesh.dropped_hidden())},
                        {"exposure_stops", exposed.exposure}})}) {
    if (!s.ok()) return s;
  }
  return Ok{};
}

}  // namespace

int RunRender(const RenderOptions& options) {
  Result<Job> job = LoadJob(options.scene);
  if (!job.ok()) {
    PrintError(job.error());
    return kExitBadInput;
  }
  if (Status s = ApplyOverrides(options, &*job); !s.ok()) {
    PrintError(s.error());
    return kExitBadInput;
  }
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  if (!scene.ok()) {
    PrintError(scene.error());
    return kExitBadInput;
  }
  PrintWarnings(scene->warnings);
  std::vector<std::string> mesh_warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(*scene, job->mesh, &mesh_warnings);
  PrintWarnings(mesh_warnings);
  if (!mesh.ok()) {
    PrintError(mesh.error());
    return kExitBadInput;
  }

  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) {
    PrintError(options.out_dir + ": cannot create the output directory: " + ec.message());
    return kExitFailure;
  }

  const PatchScene& patches = mesh->patch_scene();
  if (!options.quiet) {
    std::printf("%s: %zu patches (target size %g), sampler %s, seed %llu\n",
                job->scene_path.c_str(), patches.patches.size(), mesh->patch_size(),
                std::string(SamplerName(job->solver.sampler)).c_str(),
                static_cast<unsigned long long>(job->solver.seed));
  }
  ProgressReporter reporter(stdout, isatty(STDOUT_FILENO) == 1);
  SolveResult solution;
  try {
    solution = Solve(patches, job->solver, [&](const RoundProgress& p) {
      if (!options.quiet) reporter.OnRound(p);
    });
  } catch (const std::exception& e) {
    // Embree failures (out of memory, unsupported CPU) are the only exceptions the core throws.
    reporter.Finish();
    PrintError(std::string("solve failed: ") + e.what());
    return kExitFailure;
  }
  reporter.Finish();

  if (Status s = WriteOutputs(options.out_dir, *mesh, solution, *job); !s.ok()) {
    PrintError(s.error());
    return kExitFailure;
  }
  if (!options.quiet) {
    const SolveStats& st = solution.stats;
    std::printf(
        "%s after %llu rounds: unshot %.4f%%, %llu rays in %.2f s (%.2f Mrays/s); wrote %s\n",
        st.stop_reason.c_str(), static_cast<unsigned long long>(st.rounds),
        100 * st.unshot_fraction, static_cast<unsigned long long>(st.rays), st.seconds,
        st.rays_per_second / 1e6, options.out_dir.c_str());
  }
  return kExitOk;
}

}  // namespace radfarm
