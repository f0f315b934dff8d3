// Scenes, secrets and assignments for the agent tests, and the reference result: a batch computed
// locally with BatchTracer, which the agent's answer must equal bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/batch.h"
#include "core/patch_scene.h"
#include "core/solver_settings.h"
#include "protocol/farm_secret.h"
#include "protocol/messages.h"

namespace radfarm::agent::testing {

// A closed box of 6 x n x n patches, one material.
PatchScene BoxScene(int n);
// BoxScene(n) with every patch's reflectance and emission its own (hashed from its index), so
// zstd cannot shrink the blob much: real scenes differ patch to patch; a uniform box packs 10:1.
PatchScene VariedBoxScene(int n);
// A varied box whose compressed scene takes 3 scene chunks.
inline constexpr int kBigBox = 75;

// A 32-byte secret filled with `fill`, and its key file.
protocol::FarmSecret TestSecret(uint8_t fill);
void WriteSecretFile(const std::string& path, const protocol::FarmSecret& secret);

struct TestJob {
  uint64_t job_id = 1;
  SamplerKind sampler = SamplerKind::kSobol;
  uint64_t seed = 7;
  double grid_step_degrees = 10;
};

inline TestJob Job(uint64_t job_id, SamplerKind sampler = SamplerKind::kSobol, uint64_t seed = 7,
                   double grid_step_degrees = 10) {
  return TestJob{job_id, sampler, seed, grid_step_degrees};
}

// The assignment of rays [first_ray, first_ray + ray_count) of `shooter` in `round`.
protocol::AssignedBatch Assignment(const TestJob& job, const std::vector<uint8_t>& blob,
                                   const PatchScene& scene, uint64_t batch_id, uint32_t shooter,
                                   uint64_t first_ray, uint32_t ray_count, uint32_t round = 0);

// Rays of a batch that must still be running when the agent notices something (a user back, a
// lost connection): about 4.5 s on one core of a 2026 machine (11 M rays/s on these box scenes;
// the batch tracer has got faster before, and 5 million rays once ran for 0.44 s, shorter than
// the idle policy's 1 s poll), and a few times that under sanitizers, within the tests' waits.
constexpr uint32_t kLongBatchRays = 50'000'000;

// What BatchTracer::Run gives for the assignment on this machine.
BatchResult RunLocally(const PatchScene& scene, const protocol::AssignedBatch& assignment);

// --master, --secret-file, --threads, --name and --log-level debug, then `extra`.
std::vector<std::string> AgentArgs(const std::string& master, const std::string& secret_file,
                                   unsigned threads, std::vector<std::string> extra = {});

}  // namespace radfarm::agent::testing
