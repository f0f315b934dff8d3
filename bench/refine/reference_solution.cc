#include "bench/refine/reference_solution.h"

#include <chrono>
#include <stdexcept>

#include "core/solve.h"
#include "mesh/patch_mesh.h"

namespace radfarm::bench {
namespace {

// Seeds no row uses (rows run seed 1): a shared seed would share their first rays.
constexpr uint64_t kSeeds[2] = {1000003, 2000003};

}  // namespace

ReferenceSolution SolveReference(const InputScene& scene, double patch_size, uint64_t shot_rays,
                                 const Camera& camera) {
  Result<PatchMesh> mesh = PatchMesh::Build(scene, {patch_size}, nullptr);
  if (!mesh.ok()) throw std::runtime_error(mesh.error());
  ReferenceSolution ref;
  ref.patch_size = patch_size;
  ref.scene = mesh->patch_scene();
  ref.shot_rays = shot_rays;
  const size_t n = ref.scene.patches.size();
  std::vector<Rgb> mean(n), mean_unshot(n);
  ref.mean.assign(n, 0);
  ref.half_diff.assign(n, 0);
  for (int k = 0; k < 2; ++k) {
    SolverSettings s;
    s.shot_rays = shot_rays;
    s.tolerance = 1e-4;
    s.seed = kSeeds[k];
    const auto start = std::chrono::steady_clock::now();
    const SolveResult r = Solve(ref.scene, s);
    ref.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ref.rays += r.stats.rays;
    const double sign = k == 0 ? 0.5 : -0.5;
    for (size_t i = 0; i < n; ++i) {
      mean[i] += r.radiosity[i] * 0.5;
      mean_unshot[i] += r.unshot[i] * 0.5;
      ref.mean[i] += 0.5 * r.radiosity[i].Sum();
      ref.half_diff[i] += sign * r.radiosity[i].Sum();
    }
  }
  mesh->SetSolution(mean, mean_unshot);
  const DisplayMesh display = mesh->MakeDisplayMesh();
  ref.image = RenderImage(display, ResolveCamera(display, camera));
  for (const Rgb& p : ref.image.pixels) ref.image_mean += p.Sum();
  ref.image_mean /= double(ref.image.pixels.size());
  return ref;
}

}  // namespace radfarm::bench
