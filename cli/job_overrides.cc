#include "cli/job_overrides.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cstdint>

#include "cli/option_checks.h"
#include "core/thread_pool.h"
#include "job/job.h"

namespace radfarm {
namespace {

// 0 or a side in the job file's range, refused in its words.
CLI::Validator LightmapSizeCheck() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        int64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error != std::errc() || stop != end || !IsValidLightmapSize(value)) {
          return "must be " + LightmapSizeRange() + ", got '" + text + "'";
        }
        return "";
      },
      "N");
}

}  // namespace

void AddJobOverrideOptions(CLI::App* command, JobOverrides* overrides) {
  command->add_option("--seed", overrides->seed, "Random seed (default 1)")
      ->check(UnsignedInteger());
  command
      ->add_option("--tolerance", overrides->tolerance,
                   "Stop when unshot power < T x emitted power (default 0.001)")
      ->check(RealIn(ToleranceRange()));
  command->add_option("--rays", overrides->rays, "Stop after N rays (default: no limit)")
      ->check(PositiveInteger());
  command
      ->add_option(
          "--seconds", overrides->seconds,
          "Time budget in seconds: reading the scene, the solve, the display and the outputs "
          "(default: no limit)")
      ->check(PositiveReal());
  command->add_option("--sampler", overrides->sampler, "grid, random or sobol (default sobol)")
      ->check(CLI::IsMember({"grid", "random", "sobol"}));
  command
      ->add_option(
          "--patch-size", overrides->patch_size,
          "Largest patch edge in scene units; triangles up to sqrt(2) times it (default: per "
          "face, a tenth of its mean free path)")
      ->check(PositiveReal());
  command
      ->add_option("--max-memory", overrides->max_memory,
                   "Refuse a job whose solve would need more memory than this, e.g. 8G or 512M "
                   "(default: this machine's physical memory)")
      ->transform(ByteSize());
  command
      ->add_option(
          "--max-scene-bytes", overrides->max_scene_bytes,
          "Refuse a scene file (OBJ, MTL, glTF) larger than this, from its size before reading it, "
          "e.g. 4G (default 1G)")
      ->transform(ByteSize());
  command->add_flag("--allow-outside-files", overrides->allow_outside_files,
                    "Let the scene read files it names outside its own directory (absolute paths, "
                    "'..'): only for a scene you trust; /proc, /sys and /dev stay refused");
  command->add_option("--camera", overrides->camera,
                      "A camera of the glTF scene, by node or camera name (default: the job "
                      "file's camera, else the scene's first camera)");
  command
      ->add_option("--lightmap-size", overrides->lightmap_size,
                   "Every lightmap N x N texels, N in [16, 8192]; 0: automatic (default: the job "
                   "file's [output] lightmap_size, else by each object's area)")
      ->check(LightmapSizeCheck());
}

Status ApplyOverrides(const JobOverrides& overrides, Job* job) {
  SolverSettings& s = job->solver;
  // The job file may come from anyone (threads up to 65536): on this machine it asks for at most
  // its cores. --threads is the user's own choice, within its range.
  if (overrides.threads) {
    s.threads = *overrides.threads;
  } else {
    s.threads = std::min(s.threads, MachineThreads());
  }
  job->mesh.threads = s.threads;  // meshing uses the solve's threads (0: one per core)
  if (overrides.seed) s.seed = *overrides.seed;
  if (overrides.tolerance) s.tolerance = *overrides.tolerance;
  if (overrides.rays) s.max_rays = *overrides.rays;
  if (overrides.seconds) s.max_seconds = *overrides.seconds;
  if (overrides.patch_size) job->mesh.patch_size = *overrides.patch_size;
  if (overrides.max_memory) job->mesh.max_memory = *overrides.max_memory;
  if (overrides.lightmap_size) {
    job->lightmap_size = *overrides.lightmap_size;
    if (job->lightmap_size > 0) job->lightmap_texel = 0;  // the chosen size wins
  }
  if (overrides.sampler && !ParseSamplerName(*overrides.sampler, &s.sampler)) {
    return Error{"--sampler: unknown sampler '" + *overrides.sampler +
                 "' (expected grid, random or sobol)"};
  }
  return Ok{};
}

}  // namespace radfarm
