#include "mesh/light_scores.h"

#include <cstdio>
#include <cstdlib>

namespace radfarm {

bool ScoredElement::operator==(const ScoredElement& o) const {
  return shape.corners == o.shape.corners && shape.corner_count == o.shape.corner_count &&
         shape.normal == o.shape.normal && shape.centre == o.shape.centre &&
         reflectance == o.reflectance && surface == o.surface && radiosity == o.radiosity;
}

std::vector<uint32_t> SurfacesOf(const PatchScene& scene) {
  std::vector<uint32_t> surface_of;
  surface_of.reserve(scene.patches.size());
  for (const Patch& p : scene.patches) surface_of.push_back(p.surface);
  return surface_of;
}

std::vector<double> TraceLightScores(const LightScoreWork& work,
                                     const std::vector<uint32_t>& surface_of,
                                     const RayCaster& caster, size_t begin, size_t end,
                                     ThreadPool& pool) {
  if (begin > end || end > work.elements.size()) {
    std::fprintf(stderr, "TraceLightScores: elements [%zu, %zu) of %zu\n", begin, end,
                 work.elements.size());
    std::abort();
  }
  std::vector<double> scores(end - begin, 0.0);
  pool.ParallelFor(end - begin, [&](unsigned, size_t k) {
    const ScoredElement& e = work.elements[begin + k];
    Patch patch;
    static_cast<PatchShape&>(patch) = e.shape;
    patch.reflectance = e.reflectance;
    patch.surface = e.surface;
    scores[k] = LightScore(patch, e.radiosity, work.sources, surface_of, caster, work.tolerance);
  });
  return scores;
}

}  // namespace radfarm
