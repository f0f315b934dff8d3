#include "tests/agent/test_farm.h"

#include <fstream>

#include "codec/patch_scene_codec.h"
#include "core/batch_tracer.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"
#include "protocol/batch_convert.h"
#include "protocol/scene_transfer.h"
#include "tests/core/test_scenes.h"

namespace radfarm::agent::testing {

PatchScene BoxScene(int n) {
  radfarm::testing::Surface wall{Rgb(0.5, 0.6, 0.7), Rgb(0.1, 0.1, 0.1), 0};
  PatchScene scene = radfarm::testing::MakeClosedBox(Vec3(0, 0, 0), Vec3(2, 3, 4), n, wall);
  scene.material_names = {"wall"};
  return scene;
}

PatchScene VariedBoxScene(int n) {
  PatchScene scene = BoxScene(n);
  uint64_t x = 0x9e3779b97f4a7c15ull;
  auto next = [&x] {  // xorshift64: 53 random mantissa bits a value
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return static_cast<double>(x >> 11) / 9007199254740992.0;
  };
  for (Patch& p : scene.patches) {
    p.reflectance = Rgb(0.2 + 0.6 * next(), 0.2 + 0.6 * next(), 0.2 + 0.6 * next());
    p.emission = Rgb(0.1 * next(), 0.1 * next(), 0.1 * next());
  }
  return scene;
}

protocol::FarmSecret TestSecret(uint8_t fill) {
  const std::vector<uint8_t> bytes(32, fill);
  return protocol::FarmSecret::FromBytes(bytes).value();
}

void WriteSecretFile(const std::string& path, const protocol::FarmSecret& secret) {
  std::ofstream(path) << secret.ToHex() << "\n";
}

protocol::AssignedBatch Assignment(const TestJob& job, const std::vector<uint8_t>& blob,
                                   const PatchScene& scene, uint64_t batch_id, uint32_t shooter,
                                   uint64_t first_ray, uint32_t ray_count, uint32_t round) {
  protocol::JobWireInfo info;
  info.job_id = job.job_id;
  info.settings.sampler = job.sampler;
  info.settings.seed = job.seed;
  info.settings.grid_step_degrees = job.grid_step_degrees;
  info.scene_hash = protocol::HashScene(blob);
  info.patch_count = static_cast<uint32_t>(scene.patches.size());
  const Batch batch{round, shooter, first_ray, ray_count};
  return protocol::BatchOf(protocol::MakeLeaseAssignment(
                               info, {{batch_id, /*attempt_id=*/0, batch}}, /*lease_ms=*/60000),
                           0);
}

BatchResult RunLocally(const PatchScene& scene, const protocol::AssignedBatch& assignment) {
  const RayCaster caster(scene);
  const RaySampler sampler(assignment.sampler, assignment.seed, assignment.grid_step_degrees);
  BatchTracer runner(scene, caster, sampler);
  return runner.Run(protocol::ToBatch(assignment));
}

std::vector<std::string> AgentArgs(const std::string& master, const std::string& secret_file,
                                   unsigned threads, std::vector<std::string> extra) {
  std::vector<std::string> args{
      "--master", master,       "--secret-file", secret_file, "--threads", std::to_string(threads),
      "--name",   "test-agent", "--log-level",   "debug"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

}  // namespace radfarm::agent::testing
