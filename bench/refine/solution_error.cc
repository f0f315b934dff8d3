#include "bench/refine/solution_error.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "bench/refine/element_points.h"
#include "bench/refine/reference_image.h"
#include "core/counter_rng.h"
#include "core/direct_light.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"
#include "core/thread_pool.h"
#include "display/display_stage.h"
#include "mesh/locate_patches.h"

namespace radfarm::bench {
namespace {

// Jittered points per element edge at which the reference's direct light is averaged.
constexpr uint32_t kDirectSections = 6;

// The reference patch under each of the kPointsPerElement points of every element of `run`
// (kNoPatch where none): element e's are entries e * kPointsPerElement onwards.
std::vector<uint32_t> ReferencePatchesUnder(const PatchScene& run, const ReferenceSolution& ref) {
  std::vector<SurfacePoint> points;
  points.reserve(run.patches.size() * kPointsPerElement);
  for (const Patch& p : run.patches) AppendElementPoints(p, &points);
  return LocatePoints(ref.scene, points);
}

}  // namespace

PatchError MeasurePatchError(const PatchScene& run, const std::vector<Rgb>& radiosity,
                             const ReferenceSolution& ref) {
  const std::vector<uint32_t> under = ReferencePatchesUnder(run, ref);
  PatchError out;
  const double threshold = ref.dark_threshold;
  const size_t n = run.patches.size();
  std::vector<double> bref(n, 0), noise(n, 0);
  std::vector<char> counted(n, 1);  // not vector<bool>: written from several threads
  const RayCaster caster(ref.scene);
  const DirectLight direct(ref.scene, caster, kShadowRaysPerPoint);
  ThreadPool pool(std::max(1u, std::thread::hardware_concurrency()));
  pool.ParallelFor(n, [&](unsigned, size_t e) {
    const std::vector<uint32_t>& covered = ref.covered_surfaces;
    if (std::find(covered.begin(), covered.end(), run.patches[e].surface) != covered.end()) {
      counted[e] = false;  // under a covering sheet: out of every view
      return;
    }
    for (int k = 0; k < kPointsPerElement; ++k) {
      const uint32_t r = under[e * kPointsPerElement + k];
      if (r == kNoPatch || !(ref.mean[r] >= threshold)) {
        counted[e] = false;
        return;
      }
      bref[e] += ref.bounced[r] / kPointsPerElement;
      noise[e] += ref.half_diff[r] / kPointsPerElement;
    }
    // The direct light over the element itself, not as the reference mesh drew it.
    const Patch& p = run.patches[e];
    const PatchSampling sampling = PreparePatchSampling(p, caster.origin_offset());
    constexpr uint32_t m = kDirectSections;
    Rgb sum;
    for (uint32_t a = 0; a < m; ++a) {
      for (uint32_t b = 0; b < m; ++b) {
        const CounterRng rng(HashWords(3, e, a * m + b));
        const Vec3 x =
            SamplePatchPoint(p, sampling, (a + rng.Uniform(0)) / m, (b + rng.Uniform(1)) / m);
        sum += direct.Irradiance(x, p.normal, HashWords(4, e, a * m + b));
      }
    }
    bref[e] += (p.reflectance * sum).Sum() / double(m * m);
  });
  double area = 0, sq = 0, sq_noise = 0;
  for (size_t e = 0; e < n; ++e) {
    if (!counted[e]) continue;
    const double a = run.patches[e].area;
    const double rel = (radiosity[e].Sum() - bref[e]) / bref[e];
    const double rel_noise = noise[e] / bref[e];
    area += a;
    sq += a * rel * rel;
    sq_noise += a * rel_noise * rel_noise;
  }
  if (!(area > 0)) return out;
  out.measured = std::sqrt(sq / area);
  out.reference_noise = std::sqrt(sq_noise / area);
  out.net = std::sqrt(std::max(0.0, sq - sq_noise) / area);
  return out;
}

double MeasureImageError(const Image& image, const ReferenceSolution& ref) {
  double sum = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    sum += std::abs(image.pixels[i].Sum() - ref.image.pixels[i].Sum());
  }
  return sum / double(image.pixels.size()) / ref.image_mean;
}

ImagePartErrors MeasureImagePartErrors(PatchMesh& mesh, const SolveResult& solution,
                                       const SolverSettings& solver, const Camera& camera,
                                       const ReferenceSolution& ref) {
  const std::vector<Patch>& patches = mesh.patch_scene().patches;
  std::vector<Rgb> direct(patches.size()), rest(patches.size());
  for (size_t f = 0; f < patches.size(); ++f) {
    direct[f] = patches[f].reflectance * solution.direct_light[f];
    rest[f] = solution.radiosity[f] - direct[f];
  }
  // The rest alone: averaged over patches and extrapolated at borders, as the display does.
  const DisplayTopology topology = mesh.display_topology();
  const Image bounced = RenderImage(AveragedDisplay(topology, mesh.patch_scene(), rest), camera);
  // The direct light alone: a radiosity of rho times the patch's direct light leaves no rest.
  const Display lit_display =
      ShadeDisplay({topology, mesh.patch_scene(), mesh.patch_size(), direct, solution.direct_light},
                   {solver.seed, solver.threads});
  const Image lit = RenderImage(lit_display.mesh, camera);
  ImagePartErrors out;
  for (size_t i = 0; i < lit.pixels.size(); ++i) {
    const double ref_bounced = ref.bounced_image.pixels[i].Sum();
    out.bounced += std::abs(bounced.pixels[i].Sum() - ref_bounced);
    out.direct += std::abs(lit.pixels[i].Sum() - (ref.image.pixels[i].Sum() - ref_bounced));
  }
  const double norm = double(lit.pixels.size()) * ref.image_mean;
  out.direct /= norm;
  out.bounced /= norm;
  return out;
}

double MeasureDisplayError(PatchMesh& mesh, const SolveResult& solution,
                           const SolverSettings& solver, const Camera& camera,
                           const ReferenceSolution& ref) {
  const std::vector<Patch>& patches = mesh.patch_scene().patches;
  const std::vector<uint32_t> under = ReferencePatchesUnder(mesh.patch_scene(), ref);
  std::vector<Rgb> radiosity(patches.size());
  for (size_t e = 0; e < patches.size(); ++e) {
    const Rgb direct = patches[e].reflectance * solution.direct_light[e];
    const Rgb rest = solution.radiosity[e] - direct;
    double sum = 0;
    int found = 0;
    for (int k = 0; k < kPointsPerElement; ++k) {
      const uint32_t r = under[e * kPointsPerElement + k];
      if (r == kNoPatch) continue;
      sum += ref.bounced[r];
      ++found;
    }
    // The reference keeps channel sums: its bounced light takes the element's own colour.
    const double own = rest.Sum();
    radiosity[e] =
        found > 0 && own > 0 ? direct + rest * (sum / found / own) : solution.radiosity[e];
  }
  const DisplayTopology topology = mesh.display_topology();
  const Display display = ShadeDisplay(
      {topology, mesh.patch_scene(), mesh.patch_size(), radiosity, solution.direct_light},
      {solver.seed, solver.threads});
  return MeasureImageError(RenderImage(display.mesh, camera), ref);
}

}  // namespace radfarm::bench
