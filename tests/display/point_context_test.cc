// The display's point work traced elsewhere (display/point_context.h): a PointTracer built from a
// copy of the scene and the plan's PointContext, tracing each step's work in pieces, gives the
// display ShadeDisplay gives, bit for bit. That is what lets agents trace a job's display.
#include "display/point_context.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

#include "core/direct_light.h"
#include "core/direct_start.h"
#include "display/display_plan.h"
#include "display/display_stage.h"
#include "mesh/light_scores.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"
#include "tests/core/test_scenes.h"
#include "tests/mesh/test_scenes.h"

namespace radfarm {
namespace {

class PointContextTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<PatchMesh> built = PatchMesh::Build(testing::CornellBox(), {90}, nullptr);
    ASSERT_TRUE(built.ok()) << built.error();
    mesh_.emplace(std::move(*built));
    solver_.gather_rays = 256;
    solver_.threads = 2;
    solution_ = Solve(mesh_->patch_scene(), solver_);
    ASSERT_FALSE(solution_.direct_light.empty()) << "the solve starts from the direct light";
    topology_ = mesh_->display_topology();
  }

  DisplayInput Input() const {
    return {topology_, mesh_->patch_scene(), mesh_->patch_size(), solution_.radiosity,
            solution_.direct_light};
  }

  DisplaySettings Settings(uint64_t allowance) const {
    DisplaySettings settings;
    settings.seed = 7;
    settings.threads = 2;
    settings.emitters = EmittersInDirectStart(mesh_->patch_scene(), solver_);
    settings.rays_per_light = DirectLightRaysPerLight(mesh_->patch_scene(), solver_);
    settings.ray_allowance = allowance;
    return settings;
  }

  // Each step's work cut into pieces of `piece` points (PieceOf), each traced by a PointTracer of
  // its own on a copy of the scene on one thread, as agents do.
  Display TracedElsewhere(const DisplaySettings& settings, size_t piece) const {
    const PatchScene copy = mesh_->patch_scene();
    DisplayPlan plan(Input(), settings);
    while (const PointWork* work = plan.work()) {
      const PointTracer tracer(copy, plan.context());
      PointValues whole;
      for (size_t begin = 0; begin < work->points.size(); begin += piece) {
        const size_t end = std::min(work->points.size(), begin + piece);
        const PointWork cut = PieceOf(*work, begin, end);
        AppendPointValues(tracer.Trace(cut, 0, cut.points.size(), 1), &whole);
      }
      plan.Apply(std::move(whole));
    }
    return std::move(plan).Finish();
  }

  SolverSettings solver_;
  std::optional<PatchMesh> mesh_;
  SolveResult solution_;
  DisplayTopology topology_;
};

void ExpectSameMesh(const DisplayMesh& a, const DisplayMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_patch, b.triangle_patch);
  for (size_t v = 0; v < a.positions.size(); ++v) {
    ASSERT_EQ(a.positions[v], b.positions[v]) << "vertex " << v;
    ASSERT_EQ(a.radiance[v], b.radiance[v]) << "vertex " << v;
  }
}

TEST_F(PointContextTest, WorkTracedElsewhereInPiecesGivesShadeDisplaysBits) {
  const DisplaySettings settings = Settings(0);
  const Display here = ShadeDisplay(Input(), settings);
  ASSERT_GT(here.stats.gathered, 0u) << "some points gather: the context's arrays are used";
  ASSERT_GT(here.stats.levels, 0) << "the light bends: the levels' work is traced too";
  const Display there = TracedElsewhere(settings, 37);
  ExpectSameMesh(here.mesh, there.mesh);
  EXPECT_EQ(here.stats.rays, there.stats.rays);
}

TEST_F(PointContextTest, AFittedDirectLightIsRebuiltWithItsOwnRays) {
  // An allowance that fits fewer shadow rays per point and per light than the settings': the
  // context must carry the fitted ones, or the points elsewhere would be traced with others.
  const Display full = ShadeDisplay(Input(), Settings(0));
  std::optional<DisplaySettings> fitted;
  for (uint64_t allowance = full.stats.rays / 8; allowance > 1000 && !fitted; allowance /= 2) {
    const DisplaySettings settings = Settings(allowance);
    const Display display = ShadeDisplay(Input(), settings);
    if (display.stats.averaged) break;
    if (display.stats.rays_per_light != 0) fitted = settings;
  }
  ASSERT_TRUE(fitted) << "no allowance fits fewer shadow rays yet some";
  const Display here = ShadeDisplay(Input(), *fitted);
  const Display there = TracedElsewhere(*fitted, 101);
  ExpectSameMesh(here.mesh, there.mesh);
}

TEST_F(PointContextTest, TheContextGathersOnlyOnceTheDirectLightIsIn) {
  DisplayPlan plan(Input(), Settings(0));
  ASSERT_NE(plan.work(), nullptr);
  const PointContext first = plan.context();
  EXPECT_FALSE(first.gathers());
  EXPECT_GT(first.rays_per_point, 0u);
  const PointTracer tracer(mesh_->patch_scene(), first);
  plan.Apply(tracer.Trace(*plan.work(), 0, plan.work()->points.size(), 2));
  const PointContext second = plan.context();
  ASSERT_TRUE(second.gathers());
  const size_t patches = mesh_->patch_scene().patches.size();
  EXPECT_EQ(second.outgoing.size(), patches);
  EXPECT_EQ(second.corner_offsets.size(), patches);
  EXPECT_EQ(second.bounced.size(), patches);
}

constexpr StartWork kWork{4, 99, true, 8};

// A direct-light start traced by agents (core/direct_start.h): a PointTracer on the start's
// context, tracing start work in pieces, gives PatchDirectLight's bits and punctual power.
TEST(PointContextStartTest, AStartsPatchesTracedElsewhereInPiecesGivePatchDirectLightsBits) {
  const PatchScene scene = testing::LightsAndLampOverFloor();
  double power = 0;
  const std::vector<Rgb> whole = PatchDirectLight(scene, kWork.sections, kWork.seed, 2,
                                                  kWork.emitters, &power, kWork.rays_per_light);
  // What an agent holds: a copy of the scene and the start's context.
  const PatchScene copy = scene;
  PointContext context;
  context.emitters = kWork.emitters;
  context.rays_per_point = 1;
  context.rays_per_light = kWork.rays_per_light;
  const PointTracer tracer(copy, context);
  PointWork work;
  work.seed = kWork.seed;
  work.direct = true;
  work.start_sections = kWork.sections;
  work.start_patches = scene.patches.size();
  work.start_punctual = true;
  ASSERT_EQ(work.size(), scene.patches.size());
  PatchStartValues values;
  for (size_t begin = 0; begin < work.size(); begin += 13) {
    const size_t end = std::min(work.size(), begin + 13);
    const PointWork piece = PieceOf(work, begin, end);
    PointValues traced = tracer.Trace(piece, 0, piece.size(), 1);
    values.direct.insert(values.direct.end(), traced.direct.begin(), traced.direct.end());
    values.punctual.insert(values.punctual.end(), traced.punctual.begin(), traced.punctual.end());
    values.rays += traced.rays;
  }
  const StartLight start = StartLightOf(scene, std::move(values));
  EXPECT_TRUE(testing::BitIdentical(start.direct, whole));
  EXPECT_EQ(start.punctual_power, power);
}

// A refinement step's light scores traced by agents (mesh/light_scores.h): a PointTracer on a
// copy of the scene and a context holding the score work, tracing it in pieces, gives the scores
// the refining thread would.
TEST(PointContextScoreTest, AStepsLightScoresTracedElsewhereInPiecesGiveTheBits) {
  Result<PatchMesh> mesh = PatchMesh::Build(testing::OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const PatchScene& scene = mesh->patch_scene();
  std::vector<Rgb> unshot;
  for (const Patch& p : scene.patches) unshot.push_back(p.emission);
  PointContext context;
  context.rays_per_point = 1;
  context.scoring.sources = StrongestSources(scene, unshot, kLightSources);
  context.scoring.tolerance = 0.1;
  for (const Patch& p : scene.patches) {
    context.scoring.elements.push_back({p, p.reflectance, p.surface, p.emission});
  }
  const RayCaster caster(scene);
  ThreadPool pool(2);
  const std::vector<double> whole =
      TraceLightScores(context.scoring, SurfacesOf(scene), caster, 0, scene.patches.size(), pool);
  const PatchScene copy = scene;
  const PointTracer tracer(copy, context);
  ASSERT_EQ(tracer.score_elements(), scene.patches.size());
  PointWork work;
  work.score_elements = scene.patches.size();
  ASSERT_EQ(work.size(), scene.patches.size());
  PointValues values;
  for (size_t begin = 0; begin < work.size(); begin += 29) {
    const PointWork piece = PieceOf(work, begin, std::min(work.size(), begin + 29));
    AppendPointValues(tracer.Trace(piece, 0, piece.size(), 1), &values);
  }
  EXPECT_EQ(values.scores, whole);
  EXPECT_TRUE(values.direct.empty());
}

}  // namespace
}  // namespace radfarm
