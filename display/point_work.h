// The display's ray work: the light at a list of points, planned by the display
// (display/display_plan.h) and traced anywhere, on this machine's threads or elsewhere, in pieces
// of any size. A point's values are a pure function of the work, the lights it is traced against
// and the point's index in the work's list, so the values of every piece put together are the
// bits of the whole list traced at once: the contract the rounds' batches keep.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/direct_light.h"
#include "core/point_gather.h"
#include "core/ray_caster.h"
#include "core/rgb.h"
#include "mesh/light_scores.h"

namespace radfarm {

struct PointWork {
  std::vector<ReceiverPoint> points;
  uint64_t seed = 0;  // keys the shadow and gathering rays of point i with first_index + i
  // Where points[0] stands in the whole list: 0 for a whole step's work, the piece's first point
  // for a piece of it cut out and traced elsewhere (PieceOf).
  uint64_t first_index = 0;
  // Whether each point lies within near_radius of another surface (a point query, no ray;
  // core/point_gather.h's NearOtherSurfaces); 0: not asked.
  double near_radius = 0;
  // The direct light at every point (core/direct_light.h's PointsDirectLight).
  bool direct = false;
  // The points that gather (GatherLight), with gather_rays each; empty: none.
  std::vector<bool> gather;
  uint32_t gather_rays = 0;
  // Start work instead of points (core/direct_start.h): patches [first_index, first_index +
  // start_patches) of the scene, each lit at start_sections^2 points keyed from `seed`, traced
  // against a context of one shadow ray per point and light. `points` is empty then.
  uint32_t start_sections = 0;  // 0: point work
  uint64_t start_patches = 0;
  bool start_punctual = false;  // HasSurfacelessLight: each patch has their share too
  // A refinement step's light scores instead (mesh/light_scores.h): elements [first_index,
  // first_index + score_elements) of the context's LightScoreWork. `points` is empty then.
  uint64_t score_elements = 0;  // 0: not score work

  bool start() const { return start_sections > 0; }
  bool scores() const { return score_elements > 0; }
  // The items a piece is cut from: points, patches of start work, or elements of score work.
  size_t size() const {
    return start() ? start_patches : scores() ? score_elements : points.size();
  }
};

// The values of points [begin, end) of a PointWork, in order; an empty vector where the work did
// not ask for it.
struct PointValues {
  std::vector<bool> near;
  std::vector<Rgb> direct;
  std::vector<Rgb> gathered;
  // Start work's per patch (core/direct_start.h's PatchStartValues): its direct light is `direct`,
  // its punctual lights' share this (empty where the scene has none).
  std::vector<Rgb> punctual;
  std::vector<double> scores;  // score work's, per element
  uint64_t rays = 0;           // shadow and gathering rays cast, second bounces included
};

// What the points are traced against: the display's lights, the same for all its work. All must
// outlive the tracing.
struct PointLights {
  const PatchScene& scene;
  const RayCaster& caster;
  const DirectLight* direct = nullptr;         // for work with `direct`
  const std::vector<Rgb>* outgoing = nullptr;  // for work that gathers: GatherLight's arguments
  const PatchCornerOffsets* corners = nullptr;
  const SecondBounce* second = nullptr;
  // For score work: the step's elements and sources, and the surface of each of the scene's
  // patches (SurfacesOf).
  const LightScoreWork* scoring = nullptr;
  const std::vector<uint32_t>* surface_of = nullptr;
};

// Traces points [begin, end) of `work` on `threads` (0: all cores); of start work, its patches
// [begin, end) counted from first_index; of score work, its elements so counted.
PointValues TracePoints(const PointLights& lights, const PointWork& work, size_t begin, size_t end,
                        unsigned threads);

// Points [begin, end) of `work` as work of their own, keyed as they are in `work`: traced whole, it
// gives the values TracePoints gives them in `work`.
PointWork PieceOf(const PointWork& work, size_t begin, size_t end);

// Appends `piece`, the values of the points that follow those in `*whole`, to `*whole`.
void AppendPointValues(PointValues piece, PointValues* whole);

}  // namespace radfarm
