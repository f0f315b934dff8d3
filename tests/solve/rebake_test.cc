// Re-bakes (RoundDriver::WarmStart, core/warm_start.h) in a furnished room lit by eight lamps,
// judged as the full solve is: against the path-traced reference at patch centres. A re-bake
// must land within the full solve's own error of the changed scene, cast far fewer rays, and give
// the same bits on any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bench/rebake/furnished_room.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"
#include "solve/previous_solve.h"

namespace radfarm {
namespace {

using bench::FurnishedRoom;
using bench::PatchReference;
using bench::RmsError;
using bench::RoomChange;
using bench::TracePatchReference;

SolverSettings Settings(uint32_t threads = 2, uint32_t gather_rays = kDefaultGatherRays) {
  SolverSettings s{.gather_rays = gather_rays};
  s.tolerance = 1e-3;
  s.threads = threads;
  return s;
}

PatchMesh Meshed(const InputScene& scene) {
  Result<PatchMesh> mesh = PatchMesh::Build(scene, MeshSettings{.patch_size = 0.25}, nullptr);
  EXPECT_TRUE(mesh) << mesh.error();
  return std::move(*mesh);
}

struct Solved {
  SolveResult solution;
  PatchScene scene;
};

// With `previous`, a re-bake from it; `reuse_start`: its direct light plus the change's is the
// start, as `render --from` makes it where no lamp changed (cli/rebake_inputs.h).
Solved SolveRoom(const RoomChange& change, const PreviousPatchValues* previous = nullptr,
                 uint32_t threads = 2, bool reuse_start = false,
                 uint32_t gather_rays = kDefaultGatherRays) {
  RefiningHooks hooks;
  hooks.previous = previous;
  if (reuse_start) hooks.start = RebakeStart(*previous, threads);
  Result<RefiningSolveResult> solved = SolveRefining(
      Meshed(FurnishedRoom(change)), Settings(threads, gather_rays), RefineSettings{}, {}, hooks);
  EXPECT_TRUE(solved) << solved.error();
  return {std::move(solved->solution), solved->mesh->patch_scene()};
}

// The root mean square of a's relative difference from b, over the patches b lights.
double RmsDifference(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!(b[i].Sum() > 1e-3)) continue;
    const double d = a[i].Sum() / b[i].Sum() - 1;
    sum += d * d;
    ++n;
  }
  return n == 0 ? 0 : std::sqrt(sum / double(n));
}

uint64_t RaysOf(const SolveResult& s) { return s.stats.rays + s.stats.start_rays; }

// One change, judged: the re-bake from `before`'s solution against a full solve of `after`.
// `gather_rays` 0: no direct start and no gather, the emitters shoot (their change too).
void ExpectRebakeAsGoodAsFull(const RoomChange& before, const RoomChange& after,
                              uint32_t gather_rays = kDefaultGatherRays) {
  const Solved old = SolveRoom(before, nullptr, 2, false, gather_rays);
  const PreviousPatchValues previous = PreviousValuesOf(old.scene, old.solution);
  const Solved full = SolveRoom(after, nullptr, 2, false, gather_rays);
  const Solved rebake = SolveRoom(after, &previous, 2, true, gather_rays);
  ASSERT_EQ(rebake.solution.radiosity.size(), full.solution.radiosity.size());
  const PatchReference ref = TracePatchReference(FurnishedRoom(after), full.scene, 37, 0.01, 2);
  ASSERT_GE(ref.patches.size(), 20u);
  const double full_error = RmsError(full.solution.radiosity, ref);
  const double rebake_error = RmsError(rebake.solution.radiosity, ref);
  SCOPED_TRACE(::testing::Message()
               << "error against the reference: full " << full_error << ", re-bake " << rebake_error
               << "; rays: full " << RaysOf(full.solution) << ", re-bake "
               << RaysOf(rebake.solution));
  // The re-bake is as close as the full solve, its noise and the residual's included.
  EXPECT_LE(rebake_error, 1.2 * full_error);
  // The change matters, and the re-bake made it: patch by patch, the previous solution is far
  // from the full solve of the changed scene, the re-bake close to it (both solves' noise apart).
  const double stale_gap = RmsDifference(old.solution.radiosity, full.solution.radiosity);
  const double rebake_gap = RmsDifference(rebake.solution.radiosity, full.solution.radiosity);
  SCOPED_TRACE(::testing::Message() << "from the full solve: the previous solution " << stale_gap
                                    << ", the re-bake " << rebake_gap);
  EXPECT_GT(stale_gap, 0.05);
  EXPECT_LT(rebake_gap, stale_gap / 4);
  // And costs at most a quarter of it in rays (shadow rays of its start included).
  EXPECT_LE(4 * RaysOf(rebake.solution), RaysOf(full.solution));
}

TEST(RebakeTest, DimmingOneLampOfEight) { ExpectRebakeAsGoodAsFull({}, {.lamp0_scale = 0.2}); }

// Without the direct start the dimmed lamp's patches shoot their change as negative light.
TEST(RebakeTest, DimmingOneLampOfEightWithoutTheDirectStart) {
  ExpectRebakeAsGoodAsFull({}, {.lamp0_scale = 0.2}, 0);
}

TEST(RebakeTest, ReflectanceChanges) {
  ExpectRebakeAsGoodAsFull({}, {.wall = {0.8, 0.75, 0.7}, .table = {0.1, 0.1, 0.1}});
}

TEST(RebakeTest, SameBitsOnAnyThreads) {
  const Solved old = SolveRoom({});
  const PreviousPatchValues previous = PreviousValuesOf(old.scene, old.solution);
  const Solved one = SolveRoom({.lamp0_scale = 0.2}, &previous, 1, true);
  const Solved three = SolveRoom({.lamp0_scale = 0.2}, &previous, 3, true);
  EXPECT_EQ(one.solution.radiosity, three.solution.radiosity);
  EXPECT_EQ(one.solution.unshot, three.solution.unshot);
  EXPECT_GT(one.solution.stats.rounds, 0u);
}

TEST(RebakeTest, NothingChangedShootsNothing) {
  const Solved old = SolveRoom({});
  const PreviousPatchValues previous = PreviousValuesOf(old.scene, old.solution);
  const Solved again = SolveRoom({}, &previous, 2, true);
  EXPECT_EQ(RaysOf(again.solution), 0u);
  ASSERT_EQ(again.solution.radiosity.size(), old.solution.radiosity.size());
  for (size_t i = 0; i < old.solution.radiosity.size(); ++i) {
    // (B - E) / rho * rho rounds back to within an ulp or two.
    EXPECT_NEAR(again.solution.radiosity[i].Sum(), old.solution.radiosity[i].Sum(),
                1e-12 * (1 + old.solution.radiosity[i].Sum()));
  }
}

TEST(RebakeTest, APatchThatWasBlackCannotBeRebaked) {
  const Solved old = SolveRoom({.table = {0, 0, 0}});
  const PreviousPatchValues previous = PreviousValuesOf(old.scene, old.solution);
  RefiningHooks hooks;
  hooks.previous = &previous;
  Result<RefiningSolveResult> solved =
      SolveRefining(Meshed(FurnishedRoom({})), Settings(), RefineSettings{}, {}, hooks);
  ASSERT_FALSE(solved);
  EXPECT_NE(solved.error().find("was black and now reflects"), std::string::npos) << solved.error();
}

}  // namespace
}  // namespace radfarm
