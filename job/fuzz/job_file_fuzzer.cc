// libFuzzer target: a TOML job file (written as job.toml) through LoadJob. Any input must give a
// job or an error naming the file: no crash, leak, UB or hang.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "base/fuzz/fuzz_files.h"
#include "job/job.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::fuzz;
  const std::filesystem::path path = FuzzScratchDirectory() / "job.toml";
  WriteFuzzFile(path, SplitFuzzInput(std::span(data, size), 1)[0]);
  auto job = radfarm::LoadJob(path.string());
  if (job && job->scene_path.empty()) std::abort();  // a job always names its scene
  if (!job && job.error().rfind(path.string(), 0) != 0) std::abort();  // errors name the file
  return 0;
}
