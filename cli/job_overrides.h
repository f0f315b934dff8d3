// Command-line overrides of a job's settings, shared by `radfarm render` and `radfarm submit` so
// both read and apply them the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "base/result.h"
#include "job/job.h"

namespace CLI {
class App;
}

namespace radfarm {

// Unset means "as the job file says".
struct JobOverrides {
  std::optional<uint32_t> threads;  // render only: a farm job's threads are the agents' business
  std::optional<uint64_t> seed;
  std::optional<double> tolerance;
  std::optional<uint64_t> rays;
  std::optional<double> seconds;
  std::optional<std::string> sampler;
  std::optional<double> patch_size;
  std::optional<uint64_t> max_memory;  // bytes; the machine's memory when unset
  // The OBJ's and each MTL's size at most, checked before reading; 1 GiB when unset.
  std::optional<uint64_t> max_scene_bytes;
  std::optional<std::string> camera;      // a camera of the scene file by name (Job::camera_name)
  std::optional<uint32_t> lightmap_size;  // Job::lightmap_size; 0: automatic
  // The scene may read files outside its own directory (input/scene_directory.h): the user's
  // explicit trust, never the job file's.
  bool allow_outside_files = false;
};

// Adds --seed, --tolerance, --rays, --seconds, --sampler, --patch-size, --max-memory,
// --max-scene-bytes, --allow-outside-files, --camera and --lightmap-size (not --threads).
void AddJobOverrideOptions(CLI::App* command, JobOverrides* overrides);

// Applies the overrides on top of the job file's settings. Errors name the option. The threads
// this machine uses (solve and meshing) are --threads, else the job file's within this machine's
// cores.
Status ApplyOverrides(const JobOverrides& overrides, Job* job);

}  // namespace radfarm
