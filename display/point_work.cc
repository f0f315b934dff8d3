#include "display/point_work.h"

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "core/direct_start.h"
#include "core/thread_pool.h"

namespace radfarm {

PointValues TracePoints(const PointLights& lights, const PointWork& work, size_t begin, size_t end,
                        unsigned threads) {
  if (begin > end || end > work.size()) {
    std::fprintf(stderr, "TracePoints: items [%zu, %zu) of %zu\n", begin, end, work.size());
    std::abort();
  }
  if (work.start()) {
    const StartWork start{work.start_sections, work.seed};
    PatchStartValues patches =
        TraceStartPatches(lights.scene, *lights.direct, lights.caster, start,
                          work.first_index + begin, work.first_index + end, threads);
    PointValues out;
    out.direct = std::move(patches.direct);
    out.punctual = std::move(patches.punctual);
    out.rays = patches.rays;
    return out;
  }
  if (work.scores()) {
    if (lights.scoring == nullptr || lights.surface_of == nullptr ||
        work.first_index + end > lights.scoring->elements.size()) {
      std::fprintf(stderr, "TracePoints: score elements [%zu, %zu) past the context's\n",
                   size_t(work.first_index + begin), size_t(work.first_index + end));
      std::abort();
    }
    ThreadPool pool(threads);
    PointValues out;
    out.scores = TraceLightScores(*lights.scoring, *lights.surface_of, lights.caster,
                                  work.first_index + begin, work.first_index + end, pool);
    return out;
  }
  const std::vector<ReceiverPoint> points(work.points.begin() + begin, work.points.begin() + end);
  PointValues out;
  if (work.near_radius > 0) {
    out.near = NearOtherSurfaces(lights.scene, lights.caster, points, work.near_radius, threads);
  }
  if (!work.gather.empty()) {
    const std::vector<bool> gather(work.gather.begin() + begin, work.gather.begin() + end);
    out.gathered = GatherLight(lights.caster, *lights.outgoing, points, gather, work.seed, threads,
                               work.gather_rays, lights.corners, lights.second, &out.rays,
                               work.first_index + begin);
  }
  if (work.direct) {
    out.direct = PointsDirectLight(*lights.direct, points, work.seed, threads, &out.rays,
                                   work.first_index + begin);
  }
  return out;
}

PointWork PieceOf(const PointWork& work, size_t begin, size_t end) {
  if (begin > end || end > work.size()) {
    std::fprintf(stderr, "PieceOf: items [%zu, %zu) of %zu\n", begin, end, work.size());
    std::abort();
  }
  PointWork piece;
  if (work.start()) {
    piece.start_sections = work.start_sections;
    piece.start_patches = end - begin;
    piece.start_punctual = work.start_punctual;
  } else if (work.scores()) {
    piece.score_elements = end - begin;
  } else {
    piece.points.assign(work.points.begin() + begin, work.points.begin() + end);
  }
  piece.seed = work.seed;
  piece.first_index = work.first_index + begin;
  piece.near_radius = work.near_radius;
  piece.direct = work.direct;
  if (!work.gather.empty())
    piece.gather.assign(work.gather.begin() + begin, work.gather.begin() + end);
  piece.gather_rays = work.gather_rays;
  return piece;
}

void AppendPointValues(PointValues piece, PointValues* whole) {
  whole->near.insert(whole->near.end(), piece.near.begin(), piece.near.end());
  whole->direct.insert(whole->direct.end(), piece.direct.begin(), piece.direct.end());
  whole->gathered.insert(whole->gathered.end(), piece.gathered.begin(), piece.gathered.end());
  whole->punctual.insert(whole->punctual.end(), piece.punctual.begin(), piece.punctual.end());
  whole->scores.insert(whole->scores.end(), piece.scores.begin(), piece.scores.end());
  whole->rays += piece.rays;
}

}  // namespace radfarm
