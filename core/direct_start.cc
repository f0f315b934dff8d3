#include "core/direct_start.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "core/counter_rng.h"
#include "core/ray_sampler.h"
#include "core/thread_pool.h"

namespace radfarm {

std::optional<StartWork> StartWorkOf(const PatchScene& scene, const SolverSettings& settings) {
  const DirectStartDecision d = DecideDirectStart(scene, settings);
  if (d.sections == 0) return std::nullopt;
  return StartWork{d.sections, settings.seed, d.emitters, d.rays_per_light};
}

DirectLight StartDirectLight(const PatchScene& scene, const RayCaster& caster,
                             const StartWork& work) {
  return DirectLight(scene, caster, 1, work.emitters, kExactLights, kLightCut, work.rays_per_light);
}

PatchStartValues TraceStartPatches(const PatchScene& scene, const DirectLight& direct,
                                   const RayCaster& caster, const StartWork& work, size_t begin,
                                   size_t end, unsigned threads) {
  if (begin > end || end > scene.patches.size()) {
    std::fprintf(stderr, "TraceStartPatches: patches [%zu, %zu) of %zu\n", begin, end,
                 scene.patches.size());
    std::abort();
  }
  const size_t n = end - begin;
  PatchStartValues out;
  out.direct.resize(n);
  if (HasSurfacelessLight(scene)) out.punctual.resize(n);
  // Per patch, so that the count is a sum of integers in a fixed order whatever the threads.
  std::vector<uint32_t> rays(n);
  const uint32_t m = std::max(1u, work.sections);
  // Stream constant: keeps these keys apart from every other use of the seed.
  const uint64_t stream = HashWords(work.seed, 0x6469726563746cull);
  ThreadPool pool(threads);
  pool.ParallelFor(n, [&](unsigned, size_t k) {
    const size_t i = begin + k;
    const Patch& p = scene.patches[i];
    const PatchSampling sampling = PreparePatchSampling(p, caster.origin_offset());
    Rgb sum, lamps;
    uint64_t cast = 0;
    for (uint32_t a = 0; a < m; ++a) {
      for (uint32_t b = 0; b < m; ++b) {
        const CounterRng rng(HashWords(stream, i, a * m + b));
        const Vec3 x =
            SamplePatchPoint(p, sampling, (a + rng.Uniform(0)) / m, (b + rng.Uniform(1)) / m);
        sum += direct.EmitterIrradiance(x, p.normal, HashWords(stream, i, a * m + b, 1), nullptr,
                                        &cast);
        if (!out.punctual.empty()) {
          lamps +=
              direct.PunctualIrradiance(x, p.normal, HashWords(stream, i, a * m + b, 2), &cast);
        }
      }
    }
    rays[k] = static_cast<uint32_t>(std::min<uint64_t>(cast, UINT32_MAX));
    if (out.punctual.empty()) {
      out.direct[k] = sum / double(m * m);
    } else {
      out.punctual[k] = lamps / double(m * m);
      out.direct[k] = (sum + lamps) / double(m * m);
    }
  });
  for (uint32_t r : rays) out.rays += r;
  return out;
}

void AppendStartValues(PatchStartValues piece, PatchStartValues* whole) {
  whole->direct.insert(whole->direct.end(), piece.direct.begin(), piece.direct.end());
  whole->punctual.insert(whole->punctual.end(), piece.punctual.begin(), piece.punctual.end());
  whole->rays += piece.rays;
}

StartLight StartLightOf(const PatchScene& scene, PatchStartValues whole) {
  StartLight start;
  for (size_t i = 0; i < whole.punctual.size(); ++i) {
    start.punctual_power += scene.patches[i].area * whole.punctual[i].Sum();
  }
  start.direct = std::move(whole.direct);
  start.shadow_rays = whole.rays;
  return start;
}

}  // namespace radfarm
