#include "mesh/refine.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <numeric>
#include <sstream>

#include "mesh/element_split.h"
#include "mesh/memory_estimate.h"
#include "mesh/polygon.h"
#include "mesh/refine_criteria.h"
#include "mesh/vertex_averages.h"

namespace radfarm {
namespace {

// Smallest allowed minimum element size, in welding tolerances: far from anything welding merges.
constexpr double kMinElementInWelds = 100;

struct Element {
  Patch patch;
  Rgb radiosity;
  Rgb unshot;
  uint32_t parent = 0;
  bool fresh = false;  // made by a split in this step
};

Patch ChildPatch(const Patch& parent, const PieceCorners& piece) {
  Patch p = parent;
  p.corners = piece.corners;
  p.corner_count = piece.count;
  const std::vector<Vec3> corners(piece.corners.begin(), piece.corners.begin() + piece.count);
  p.centre = AreaCentroid(corners);
  p.area = Length(VectorArea(corners));
  return p;
}

// Splits the elements whose score exceeds 1, highest first (ties by position), while the budget
// allows; children replace their parent in place and are marked fresh. Returns the splits made.
uint64_t SplitScored(const std::vector<double>& score, uint64_t max_elements,
                     std::vector<Element>* elements) {
  std::vector<uint32_t> chosen;
  for (uint32_t i = 0; i < score.size(); ++i) {
    if (score[i] > 1) chosen.push_back(i);
  }
  std::sort(chosen.begin(), chosen.end(), [&](uint32_t a, uint32_t b) {
    return score[a] != score[b] ? score[a] > score[b] : a < b;
  });
  const uint64_t room = max_elements > elements->size() ? max_elements - elements->size() : 0;
  chosen.resize(std::min<uint64_t>(chosen.size(), room / 3));
  std::vector<bool> split(elements->size(), false);
  for (uint32_t i : chosen) split[i] = true;
  std::vector<Element> out;
  out.reserve(elements->size() + 3 * chosen.size());
  for (uint32_t i = 0; i < elements->size(); ++i) {
    Element& e = (*elements)[i];
    if (!split[i]) {
      e.fresh = false;
      out.push_back(e);
      continue;
    }
    for (const PieceCorners& piece : SplitElement(e.patch)) {
      out.push_back({ChildPatch(e.patch, piece), e.radiosity, e.unshot, e.parent, true});
    }
  }
  *elements = std::move(out);
  return chosen.size();
}

bool Splittable(const Patch& p, double min_element_size) {
  return p.emission.Max() == 0 && LongestPatchEdge(p) >= 2 * min_element_size;
}

// The light scores of `chosen` elements, in their order: traced where `source` says, else on
// `pool`.
std::vector<double> ScoreLight(const std::vector<Element>& elements,
                               const std::vector<uint32_t>& chosen, const PatchScene& scene,
                               const std::vector<LightSource>& sources,
                               const std::vector<uint32_t>& surface_of, double tolerance,
                               const RayCaster& caster, ThreadPool& pool,
                               const LightScoreSource& source) {
  LightScoreWork work{sources, tolerance, {}};
  if (sources.empty() || chosen.empty()) return std::vector<double>(chosen.size(), 0.0);
  work.elements.reserve(chosen.size());
  for (uint32_t i : chosen) {
    const Element& e = elements[i];
    work.elements.push_back({e.patch, e.patch.reflectance, e.patch.surface, e.radiosity});
  }
  if (source) {
    if (std::optional<std::vector<double>> traced = source(scene, work)) return std::move(*traced);
  }
  return TraceLightScores(work, surface_of, caster, 0, work.elements.size(), pool);
}

}  // namespace

uint64_t AutomaticElementBudget(size_t initial_patches, uint64_t memory_limit) {
  const uint64_t budget = kElementBudgetFactor * uint64_t(initial_patches);
  const std::optional<uint64_t> fit = PatchesThatFit(memory_limit);
  if (!fit) return budget;
  return std::min(budget, std::max<uint64_t>(initial_patches, *fit));
}

Result<ResolvedRefineSettings> ResolveRefineSettings(const RefineSettings& settings,
                                                     double patch_size, size_t initial_patches,
                                                     double weld_tolerance, uint64_t memory_limit) {
  ResolvedRefineSettings out;
  if (!(settings.tolerance > 0) || !std::isfinite(settings.tolerance)) {
    return Error{"mesh.refine_tolerance must be a finite number > 0"};
  }
  out.tolerance = settings.tolerance;
  out.min_element_size =
      settings.min_element_size > 0 ? settings.min_element_size : patch_size / kMinElementDivisions;
  if (!(out.min_element_size >= kMinElementInWelds * weld_tolerance)) {
    std::ostringstream msg;
    msg << "mesh.min_element_size " << out.min_element_size << " is below "
        << kMinElementInWelds * weld_tolerance << " (1e-4 of the scene's diagonal)";
    return Error{msg.str()};
  }
  out.max_elements = settings.max_elements > 0
                         ? settings.max_elements
                         : AutomaticElementBudget(initial_patches, memory_limit);
  return out;
}

const RefinePoint* PassedRefinePoint(double unshot_fraction, size_t* next) {
  const RefinePoint* passed = nullptr;
  while (*next < std::size(kRefinePoints) &&
         unshot_fraction < kRefinePoints[*next].unshot_fraction) {
    passed = &kRefinePoints[(*next)++];
  }
  return passed;
}

CarriedState CarryOver(RefinedMesh& refined, const EnergyAccount& energy, bool restart) {
  CarriedState out;
  const PatchScene& scene = refined.mesh.patch_scene();
  out.energy = energy;
  out.restart = restart;
  if (restart) {
    out.energy = EnergyAccount{};
    out.energy.emitted = energy.emitted;
    for (const Patch& p : scene.patches) {
      out.radiosity.push_back(p.emission);
      out.unshot.push_back(p.emission);
    }
  } else {
    out.radiosity = std::move(refined.radiosity);
    out.unshot = std::move(refined.unshot);
  }
  out.energy.unshot = 0;
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    out.energy.unshot += scene.patches[i].area * out.unshot[i].Sum();
  }
  return out;
}

RefinedMesh Refine(const PatchMesh& mesh, const std::vector<Rgb>& radiosity,
                   const std::vector<Rgb>& unshot, double ray_power,
                   const ResolvedRefineSettings& settings, const RayCaster& caster,
                   ThreadPool& pool, const LightScoreSource& scores) {
  const PatchScene& scene = mesh.patch_scene();
  if (radiosity.size() != scene.patches.size() || unshot.size() != scene.patches.size()) {
    std::fprintf(stderr, "Refine: %zu radiosities, %zu unshot values, %zu patches\n",
                 radiosity.size(), unshot.size(), scene.patches.size());
    std::abort();
  }
  // The solution at the display vertices, as Gouraud shading shows it, for GradientScore.
  const std::vector<Rgb> vertex_value =
      SmoothVertexValues(mesh.display_topology(), scene, radiosity);
  const OmMesh& om = mesh.mesh();
  const std::vector<uint32_t> surface_of = SurfacesOf(scene);
  const std::vector<LightSource> sources = StrongestSources(scene, unshot, kLightSources);

  std::vector<Element> elements;
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    elements.push_back({scene.patches[i], radiosity[i], unshot[i], i, false});
  }
  std::vector<uint32_t> chosen;
  for (uint32_t i = 0; i < elements.size(); ++i) {
    if (Splittable(elements[i].patch, settings.min_element_size)) chosen.push_back(i);
  }
  std::vector<double> score(elements.size(), 0.0);
  {
    const std::vector<double> light = ScoreLight(elements, chosen, scene, sources, surface_of,
                                                 settings.tolerance, caster, pool, scores);
    for (size_t k = 0; k < chosen.size(); ++k) score[chosen[k]] = light[k];
  }
  pool.ParallelFor(chosen.size(), [&](unsigned, size_t k) {
    const uint32_t i = chosen[k];
    const Element& e = elements[i];
    std::array<OmMesh::VertexHandle, 4> corners;
    const int n = FaceCorners(om, om.face_handle(static_cast<int>(i)), &corners);
    std::vector<Rgb> vertex_radiance;
    for (int c = 0; c < n; ++c) {
      vertex_radiance.push_back(vertex_value[om.property(mesh.properties().group, corners[c])]);
    }
    score[i] = std::max(score[i], GradientScore(e.patch, e.radiosity, vertex_radiance, ray_power,
                                                settings.tolerance));
  });
  uint64_t splits = SplitScored(score, settings.max_elements, &elements);
  uint64_t total_splits = splits;
  // Children of a split are judged again by the light to come, down to the minimum size.
  while (splits > 0) {
    chosen.clear();
    for (uint32_t i = 0; i < elements.size(); ++i) {
      if (elements[i].fresh && Splittable(elements[i].patch, settings.min_element_size)) {
        chosen.push_back(i);
      }
    }
    const std::vector<double> light = ScoreLight(elements, chosen, scene, sources, surface_of,
                                                 settings.tolerance, caster, pool, scores);
    score.assign(elements.size(), 0.0);
    for (size_t k = 0; k < chosen.size(); ++k) score[chosen[k]] = light[k];
    splits = SplitScored(score, settings.max_elements, &elements);
    total_splits += splits;
  }

  std::vector<PatchMesh::Piece> pieces;
  for (const Element& e : elements) {
    PieceCorners corners;
    corners.corners = e.patch.corners;
    corners.count = e.patch.corner_count;
    pieces.push_back({corners, e.patch.surface, e.patch.material});
  }
  RefinedMesh out{mesh.Rebuilt(pieces, &pool), {}, {}, {}, total_splits};
  if (out.mesh.patch_scene().patches.size() != elements.size()) {
    // ResolveRefineSettings keeps elements far larger than the welding distance, so this is a bug.
    std::fprintf(stderr, "Refine: %zu elements became %zu patches\n", elements.size(),
                 out.mesh.patch_scene().patches.size());
    std::abort();
  }
  for (const Element& e : elements) {
    out.radiosity.push_back(e.radiosity);
    out.unshot.push_back(e.unshot);
    out.parent.push_back(e.parent);
  }
  return out;
}

}  // namespace radfarm
