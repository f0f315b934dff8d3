// SolveRefining's hooks (`radfarm render --db`) and RefinementSchedule: a refining solve resumed
// from any round's state, its refined mesh rebuilt from the scene alone, ends with the bits of the
// uninterrupted solve; bad resume states and refinement points are errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "core/solve_control.h"
#include "mesh/patch_mesh.h"
#include "mesh/refinement_schedule.h"
#include "solve/local_solve.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

PatchMesh Mesh() {
  Result<PatchMesh> mesh = PatchMesh::Build(testing::OccluderScene(), {0.5}, nullptr);
  EXPECT_TRUE(mesh.ok()) << mesh.error();
  return std::move(*mesh);
}

SolverSettings Solver() {
  SolverSettings s;
  s.shot_rays = 1 << 14;
  s.tolerance = 0.02;
  s.threads = 2;
  return s;
}

RefineSettings Refining() {
  RefineSettings r;
  r.enabled = true;
  r.tolerance = 0.1;
  r.min_element_size = 0.125;
  return r;
}

// A round's state as a store keeps it: copies, the refined scene included.
struct Saved {
  SolveState solve;
  std::optional<PatchScene> scene;
  uint32_t next_point = 0;
  // The state to resume from: `solve` pointing at the saved scene, its stop mark as given.
  SolveState Resume(std::optional<std::string> stop) const {
    SolveState state = solve;
    state.refined_scene = scene ? &*scene : nullptr;
    state.stop = std::move(stop);
    return state;
  }
};

Saved Save(const SolveState& c) {
  return {c, c.refined_scene ? std::optional(*c.refined_scene) : std::nullopt, c.next_point};
}

void ExpectResumesFromAnyRound(const SolverSettings& settings) {
  std::vector<Saved> saved;
  RefiningHooks hooks;
  hooks.after_round = [&](const SolveState& c) { saved.push_back(Save(c)); };
  Result<RefiningSolveResult> whole = SolveRefining(Mesh(), settings, Refining(), {}, hooks);
  ASSERT_TRUE(whole.ok()) << whole.error();
  ASSERT_EQ(saved.size(), whole->solution.stats.rounds);
  // With the final gather on, the refined mesh's solve gathered: no unshot is left.
  const bool gathered = whole->solution.unshot == std::vector<Rgb>(whole->solution.unshot.size());
  EXPECT_EQ(gathered, settings.gather_rays > 0);
  // The states straddle every refinement point, the later ones on a refined mesh.
  ASSERT_EQ(saved.back().next_point, std::size(kRefinePoints));
  ASSERT_TRUE(saved.back().scene.has_value());
  EXPECT_EQ(saved.back().scene->patches.size(), whole->mesh->patch_scene().patches.size());
  EXPECT_GT(whole->mesh->patch_scene().patches.size(), whole->patches_before);
  // The first state past each point, and states later on.
  std::vector<size_t> picks;
  for (uint32_t point = 0; point <= std::size(kRefinePoints); ++point) {
    for (size_t i = 0; i < saved.size(); ++i) {
      if (saved[i].next_point == point) {
        picks.push_back(i);
        break;
      }
    }
  }
  ASSERT_GE(saved.size(), 3u);
  for (size_t i : {saved.size() / 2, saved.size() - 2}) {
    if (std::find(picks.begin(), picks.end(), i) == picks.end()) picks.push_back(i);
  }
  ASSERT_GE(picks.size(), 2u);
  for (size_t i : picks) {
    SCOPED_TRACE("resumed after round " + std::to_string(saved[i].solve.round));
    const SolveState state = saved[i].Resume(std::nullopt);
    RefiningHooks resume;
    resume.resume = &state;
    Result<RefiningSolveResult> rest = SolveRefining(Mesh(), settings, Refining(), {}, resume);
    ASSERT_TRUE(rest.ok()) << rest.error();
    EXPECT_EQ(rest->mesh->patch_scene().patches.size(), whole->mesh->patch_scene().patches.size());
    EXPECT_EQ(rest->solution.radiosity, whole->solution.radiosity);
    EXPECT_EQ(rest->solution.unshot, whole->solution.unshot);
    EXPECT_EQ(rest->solution.stats.rays, whole->solution.stats.rays);
    EXPECT_EQ(rest->solution.stats.rounds, whole->solution.stats.rounds);
  }
}

TEST(RefiningResumeTest, ResumingFromAnyRoundGivesTheUninterruptedBits) {
  ExpectResumesFromAnyRound(Solver());
}

// From the restart point on, a refining solve gathers: the refined solver starts from the direct
// light (RestoreStep), and resumes on either side of the restart and of the gather end the same.
TEST(RefiningResumeTest, AGatheringRefiningSolveResumesFromAnyRound) {
  SolverSettings settings = Solver();
  settings.gather_rays = 256;
  const PatchScene scene = Mesh().patch_scene();
  ASSERT_FALSE(ProgressiveSolver(scene, settings).direct_light().empty())
      << "the light is few enough patches for the direct-light start";
  ExpectResumesFromAnyRound(settings);
}

// A solve stopped by a capped round that left rays of the budget: its last state says so, and a
// resume from it runs no round (StopBeforeRound alone would spend the rays left).
TEST(RefiningResumeTest, AResumeFromTheLastRoundOfABudgetStopRunsNoRound) {
  for (const bool refining : {true, false}) {
    SCOPED_TRACE(refining ? "refining" : "not refining");
    const RefineSettings refine = refining ? Refining() : RefineSettings{};
    SolverSettings settings = Solver();
    settings.tolerance = 1e-4;  // enough rounds
    // Proportional shots spend a budget to the ray; the grid's cannot be cut, so its capped round
    // drops whole shots and leaves some of the budget: the case that needs the mark.
    settings.sampler = SamplerKind::kGrid;
    settings.grid_step_degrees = 15;
    std::vector<uint64_t> rays_after;  // of each round, without a budget
    Result<RefiningSolveResult> unlimited = SolveRefining(
        Mesh(), settings, refine, [&](const RoundProgress& p) { rays_after.push_back(p.rays); });
    ASSERT_TRUE(unlimited.ok()) << unlimited.error();
    ASSERT_GE(rays_after.size(), 4u);
    // Budgets that cut the third round short: past the refinement point, many shooters, and
    // unconverged after it.
    settings.max_rays = rays_after[1] + (rays_after[2] - rays_after[1]) / 2;
    std::vector<Saved> saved;
    std::vector<std::optional<std::string>> stops;
    RefiningHooks hooks;
    hooks.after_round = [&](const SolveState& c) {
      saved.push_back(Save(c));
      stops.push_back(c.stop);
    };
    // A budget the capped round does not spend to the ray (the case that needs the mark).
    Result<RefiningSolveResult> whole = Error{"no budget left rays unspent"};
    for (uint64_t budget = settings.max_rays; budget < settings.max_rays + 2000; budget += 37) {
      SolverSettings capped = settings;
      capped.max_rays = budget;
      saved.clear();
      stops.clear();
      whole = SolveRefining(Mesh(), capped, refine, {}, hooks);
      ASSERT_TRUE(whole.ok()) << whole.error();
      if (whole->solution.stats.rays < budget) {
        settings = capped;
        break;
      }
    }
    ASSERT_LT(whole->solution.stats.rays, settings.max_rays);
    ASSERT_EQ(whole->solution.stats.stop_reason, kStopRayBudget);
    ASSERT_GE(stops.size(), 1u);
    for (size_t i = 0; i + 1 < stops.size(); ++i) EXPECT_FALSE(stops[i].has_value()) << i;
    ASSERT_EQ(stops.back(), std::optional<std::string>(kStopRayBudget));

    const Saved& last = saved.back();
    SolveState state = last.Resume(stops.back());
    RefiningHooks resume;
    resume.resume = &state;
    bool ran = false;
    resume.after_round = [&](const SolveState&) { ran = true; };
    Result<RefiningSolveResult> again = SolveRefining(Mesh(), settings, refine, {}, resume);
    ASSERT_TRUE(again.ok()) << again.error();
    EXPECT_FALSE(ran);
    EXPECT_EQ(again->solution.radiosity, whole->solution.radiosity);
    EXPECT_EQ(again->solution.stats.rays, whole->solution.stats.rays);
    EXPECT_EQ(again->solution.stats.rounds, whole->solution.stats.rounds);
    EXPECT_EQ(again->solution.stats.stop_reason, kStopRayBudget);

    state.stop.reset();  // without the mark: one more round, other bits
    Result<RefiningSolveResult> unmarked = SolveRefining(Mesh(), settings, refine, {}, resume);
    ASSERT_TRUE(unmarked.ok()) << unmarked.error();
    EXPECT_TRUE(ran);
    EXPECT_GT(unmarked->solution.stats.rounds, whole->solution.stats.rounds);
  }
}

TEST(RefiningResumeTest, AStateThatDoesNotFitTheMeshIsAnError) {
  SolveState state;
  state.rounds_done = 1;
  state.radiosity.resize(3);
  state.unshot.resize(3);
  state.next_point = 1;
  RefiningHooks hooks;
  hooks.resume = &state;
  Result<RefiningSolveResult> r = SolveRefining(Mesh(), Solver(), Refining(), {}, hooks);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("holds 3 elements"), std::string::npos) << r.error();

  PatchScene refined = Mesh().patch_scene();
  state.refined_scene = &refined;
  r = SolveRefining(Mesh(), Solver(), {}, {}, hooks);  // refinement off
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("unrefined"), std::string::npos) << r.error();
}

TEST(RefiningResumeTest, ScheduleRefusesPointsBeyondTheLast) {
  const PatchMesh mesh = Mesh();
  EXPECT_TRUE(RefinementSchedule::Create(Refining(), mesh, 0, std::size(kRefinePoints)).ok());
  Result<RefinementSchedule> bad =
      RefinementSchedule::Create(Refining(), mesh, 0, std::size(kRefinePoints) + 1);
  ASSERT_FALSE(bad.ok());
  const std::string beyond =
      "refinement point " + std::to_string(std::size(kRefinePoints) + 1) + " out of range";
  EXPECT_NE(bad.error().find(beyond), std::string::npos) << bad.error();
  RefineSettings tiny = Refining();
  tiny.min_element_size = 1e-12;
  Result<RefinementSchedule> unresolved = RefinementSchedule::Create(tiny, mesh, 0);
  ASSERT_FALSE(unresolved.ok());
  EXPECT_NE(unresolved.error().find("mesh.min_element_size"), std::string::npos)
      << unresolved.error();
}

}  // namespace
}  // namespace radfarm
