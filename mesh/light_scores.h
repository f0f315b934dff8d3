// The light scores of a refinement step (refine_criteria.h's LightScore), as work traced anywhere
// in pieces: the elements to judge, copied out of the mesh being refined, and the sources they are
// judged against. An element's score is a pure function of the work, the scene the ray caster is
// built on and the element's place in the list, so the scores of every piece put together are the
// bits of the whole list scored at once, on any threads or machines.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/rgb.h"
#include "core/thread_pool.h"
#include "mesh/refine_criteria.h"

namespace radfarm {

// What LightScore reads of an element: its shape, reflectance, surface and radiosity.
struct ScoredElement {
  PatchShape shape;
  Rgb reflectance;
  uint32_t surface = 0;
  Rgb radiosity;
  bool operator==(const ScoredElement& o) const;
};

struct LightScoreWork {
  std::vector<LightSource> sources;  // StrongestSources of the solution being refined
  double tolerance = 0;              // ResolvedRefineSettings::tolerance
  std::vector<ScoredElement> elements;
  bool operator==(const LightScoreWork&) const = default;
};

// The surface of every patch of `scene`, which LightScore judges visibility by.
std::vector<uint32_t> SurfacesOf(const PatchScene& scene);

// The scores of elements [begin, end) of `work`, on `pool`. `caster` is built on the scene the
// elements refine (or any refinement of it), whose patches' surfaces `surface_of` gives.
std::vector<double> TraceLightScores(const LightScoreWork& work,
                                     const std::vector<uint32_t>& surface_of,
                                     const RayCaster& caster, size_t begin, size_t end,
                                     ThreadPool& pool);

// Where a refinement step's light scores are traced: given the scene being refined and the work,
// one score per element, or nullopt to score them on the refining thread's pool. Empty: always
// there.
using LightScoreSource =
    std::function<std::optional<std::vector<double>>(const PatchScene&, const LightScoreWork&)>;

}  // namespace radfarm
