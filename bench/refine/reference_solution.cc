#include "bench/refine/reference_solution.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <string>

#include "bench/refine/reference_image.h"
#include "display/display_stage.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"

namespace radfarm::bench {
namespace {

// Seeds no row uses (rows run seed 1): a shared seed would share their first rays.
constexpr uint64_t kSeeds[2] = {1000003, 2000003};

ReferenceSolution Finish(const PatchMesh& mesh, const std::vector<Rgb>& mean, const Camera& camera,
                         ReferenceSolution ref) {
  std::vector<double> positive;
  for (double b : ref.mean) {
    if (b > 0) positive.push_back(b);
  }
  if (!positive.empty()) {
    std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
    ref.dark_threshold = kLitFraction * positive[positive.size() / 2];
  }
  const std::vector<Rgb> bounced = BouncedRadiosity(mesh.patch_scene(), mean);
  for (const Rgb& b : bounced) ref.bounced.push_back(b.Sum());
  const DisplayMesh display = AveragedDisplay(mesh.display_topology(), mesh.patch_scene(), mean);
  ref.image =
      RenderReferenceImage(mesh, bounced, ResolveCamera(display, camera), &ref.bounced_image);
  for (const Rgb& p : ref.image.pixels) ref.image_mean += p.Sum();
  ref.image_mean /= double(ref.image.pixels.size());
  return ref;
}

// The cache: n, rays, seconds, then per patch mean and half_diff (channel sums) and the mean
// radiosity and unshot (Rgb), as raw doubles. A file of another size is ignored.
template <typename T>
void Put(std::ofstream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
bool Get(std::ifstream& in, T* v) {
  return bool(in.read(reinterpret_cast<char*>(v), sizeof *v));
}

void WriteCache(const std::string& path, const ReferenceSolution& ref, const std::vector<Rgb>& mean,
                const std::vector<Rgb>& unshot) {
  std::ofstream out(path, std::ios::binary);
  Put(out, uint64_t(mean.size()));
  Put(out, ref.rays);
  Put(out, ref.seconds);
  for (size_t i = 0; i < mean.size(); ++i) {
    Put(out, ref.mean[i]);
    Put(out, ref.half_diff[i]);
    Put(out, mean[i]);
    Put(out, unshot[i]);
  }
}

bool ReadCache(const std::string& path, size_t n, ReferenceSolution* ref, std::vector<Rgb>* mean,
               std::vector<Rgb>* unshot) {
  std::ifstream in(path, std::ios::binary);
  uint64_t size = 0;
  if (!in || !Get(in, &size) || size != n || !Get(in, &ref->rays) || !Get(in, &ref->seconds)) {
    return false;
  }
  for (size_t i = 0; i < n; ++i) {
    if (!Get(in, &ref->mean[i]) || !Get(in, &ref->half_diff[i]) || !Get(in, &(*mean)[i]) ||
        !Get(in, &(*unshot)[i])) {
      return false;
    }
  }
  return true;
}

}  // namespace

ReferenceSolution SolveReference(const InputScene& scene, const std::string& name,
                                 double patch_size, uint64_t shot_rays, const Camera& camera,
                                 const std::string& cache_dir) {
  Result<PatchMesh> mesh = PatchMesh::Build(scene, {patch_size}, nullptr);
  if (!mesh.ok()) throw std::runtime_error(mesh.error());
  ReferenceSolution ref;
  ref.patch_size = patch_size;
  ref.scene = mesh->patch_scene();
  ref.covered_surfaces = mesh->covered_surfaces();
  ref.shot_rays = shot_rays;
  const size_t n = ref.scene.patches.size();
  std::vector<Rgb> mean(n), mean_unshot(n);
  ref.mean.assign(n, 0);
  ref.half_diff.assign(n, 0);
  const std::string cache = cache_dir.empty()
                                ? std::string()
                                : cache_dir + "/" + name + "-" + std::to_string(patch_size) + "-" +
                                      std::to_string(shot_rays) + "-" +
                                      std::to_string(camera.width) + ".ref";
  if (!cache.empty() && ReadCache(cache, n, &ref, &mean, &mean_unshot)) {
    return Finish(*mesh, mean, camera, std::move(ref));
  }
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
  if (!cache.empty()) WriteCache(cache, ref, mean, mean_unshot);
  return Finish(*mesh, mean, camera, std::move(ref));
}

}  // namespace radfarm::bench
