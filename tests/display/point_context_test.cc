// The display's point work traced elsewhere (display/point_context.h): a PointTracer built from a
// copy of the scene and the plan's PointContext, tracing each step's work in pieces, gives the
// display ShadeDisplay gives, bit for bit. That is what lets agents trace a job's display.
#include "display/point_context.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

#include "core/direct_light.h"
#include "display/display_plan.h"
#include "display/display_stage.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"
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

}  // namespace
}  // namespace radfarm
