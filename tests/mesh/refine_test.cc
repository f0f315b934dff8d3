// Adaptive refinement: elements gather at a known shadow edge, the refined display mesh has no
// cracks, refined and unrefined solutions agree where the light is smooth, and the refined solve
// is deterministic across thread counts and identical to Solve() when refinement is off.
#include "mesh/refine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/ray_caster.h"
#include "core/thread_pool.h"
#include "mesh/locate_patches.h"
#include "mesh/memory_estimate.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::OccluderScene;
using testing::SceneBuilder;

// Distance in x-z from the penumbra band of OccluderScene (0 inside it).
double DistanceToPenumbra(const Vec3& p) {
  auto band = [](double across, double along) {
    const double a = std::abs(across - 2), b = std::abs(along - 2);
    const double d_across = a < 0.7 ? 0.7 - a : (a > 0.9 ? a - 0.9 : 0.0);
    const double d_along = b > 0.9 ? b - 0.9 : 0.0;
    return std::hypot(d_across, d_along);
  };
  return std::min(band(p.x, p.z), band(p.z, p.x));
}

ResolvedRefineSettings Settings(double tolerance, double min_size, uint64_t max_elements) {
  return {tolerance, min_size, max_elements};
}

RefinedMesh RefineBeforeShooting(PatchMesh& mesh, const ResolvedRefineSettings& settings) {
  std::vector<Rgb> b, db;
  for (const Patch& p : mesh.patch_scene().patches) {
    b.push_back(p.emission);
    db.push_back(p.emission);
  }
  const RayCaster caster(mesh.patch_scene());
  ThreadPool pool(2);
  return Refine(mesh, b, db, 0, settings, caster, pool);
}

TEST(RefineTest, ElementsGatherAtTheShadowEdge) {
  Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  // A tolerance of 0.1: the light's smooth fall-off across the floor is interpolated far better
  // than that, the penumbra's kinks are not.
  RefinedMesh refined = RefineBeforeShooting(*mesh, Settings(0.1, 0.0625, 100000));
  ASSERT_GT(refined.split, 0u);
  double near_area = 0, far_area = 0;
  int near_count = 0, far_count = 0;
  double smallest = INFINITY;
  for (const Patch& p : refined.mesh.patch_scene().patches) {
    if (p.surface != 0) continue;  // the floor
    const double d = DistanceToPenumbra(p.centre);
    if (d < 0.1) {
      near_area += p.area;
      ++near_count;
    } else if (d > 0.6) {
      far_area += p.area;
      ++far_count;
    }
    smallest = std::min(smallest, p.area);
  }
  ASSERT_GT(near_count, 0);
  ASSERT_GT(far_count, 0);
  const double near_mean = near_area / near_count, far_mean = far_area / far_count;
  // At the edge the elements reach the minimum size; far from it they are 4x larger or more.
  EXPECT_NEAR(smallest, 0.0625 * 0.0625, 1e-9);
  EXPECT_LT(near_mean * 4, far_mean) << "near " << near_mean << ", far " << far_mean;
  // The light and the occluder keep their patches.
  for (const Patch& p : refined.mesh.patch_scene().patches) {
    if (p.surface == 2) {
      EXPECT_NEAR(p.area, 0.04, 1e-12);
    }
  }
}

TEST(RefineTest, ElementBudgetAndMinimumSizeHold) {
  Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  const size_t before = mesh->patch_scene().patches.size();
  RefinedMesh refined = RefineBeforeShooting(*mesh, Settings(0.1, 0.0625, before + 30));
  EXPECT_EQ(refined.split, 10u);
  EXPECT_EQ(refined.mesh.patch_scene().patches.size(), before + 30);
  Result<PatchMesh> again = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  RefinedMesh coarse = RefineBeforeShooting(*again, Settings(0.1, 0.25, 100000));
  for (const Patch& p : coarse.mesh.patch_scene().patches) {
    if (p.surface == 0) {
      EXPECT_GE(p.area, 0.25 * 0.25 - 1e-12);
    }
  }
}

TEST(RefineTest, TransferKeepsRadianceAndSharesUnshotPower) {
  Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  const PatchScene& before = mesh->patch_scene();
  std::vector<Rgb> b, db;
  double unshot_before = 0;
  for (size_t i = 0; i < before.patches.size(); ++i) {
    b.push_back(before.patches[i].emission + Rgb{0.01 * double(i), 0, 0});
    db.push_back(before.patches[i].emission + Rgb{0, 0.02 * double(i), 0});
    unshot_before += before.patches[i].area * db.back().Sum();
  }
  const RayCaster caster(before);
  ThreadPool pool(1);
  RefinedMesh r = Refine(*mesh, b, db, 0, Settings(0.1, 0.0625, 100000), caster, pool);
  const PatchScene& after = r.mesh.patch_scene();
  ASSERT_EQ(r.parent.size(), after.patches.size());
  double unshot_after = 0;
  for (size_t i = 0; i < after.patches.size(); ++i) {
    EXPECT_EQ(r.radiosity[i], b[r.parent[i]]);
    EXPECT_EQ(r.unshot[i], db[r.parent[i]]);
    unshot_after += after.patches[i].area * r.unshot[i].Sum();
  }
  EXPECT_NEAR(unshot_after, unshot_before, 1e-12 * unshot_before);
}

// A display vertex strictly inside another triangle's edge, on the same surface, is a crack: that
// triangle's shading does not pass through the vertex's value.
TEST(RefineTest, RefinedDisplayMeshHasNoCracks) {
  Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  RefinedMesh refined = RefineBeforeShooting(*mesh, Settings(0.1, 0.0625, 100000));
  const PatchScene& scene = refined.mesh.patch_scene();
  std::vector<Rgb> b;
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    b.push_back({std::sin(double(i)), std::cos(double(i)), 1});  // any values: they must join
  }
  const DisplayMesh d = testing::AveragedOf(refined.mesh, b);
  std::vector<uint32_t> vertex_surface(d.positions.size(), 0xffffffffu);
  std::vector<double> surface_area(3, 0.0), triangle_area(3, 0.0);
  for (size_t t = 0; t < d.triangles.size(); ++t) {
    const uint32_t surface = scene.patches[d.triangle_patch[t]].surface;
    for (uint32_t v : d.triangles[t]) vertex_surface[v] = surface;
    const auto& tri = d.triangles[t];
    triangle_area[surface] += 0.5 * Length(Cross(d.positions[tri[1]] - d.positions[tri[0]],
                                                 d.positions[tri[2]] - d.positions[tri[0]]));
  }
  for (const Patch& p : scene.patches) surface_area[p.surface] += p.area;
  for (int s = 0; s < 3; ++s) EXPECT_NEAR(triangle_area[s], surface_area[s], 1e-9);
  int t_vertices = 0;
  EXPECT_EQ(testing::FindCracks(d, scene), std::vector<std::string>{});
  // The refined floor does have T-vertices (split elements next to whole ones).
  for (uint32_t v = 0; v < d.positions.size(); ++v) {
    if (vertex_surface[v] != 0) continue;
    for (const Patch& p : scene.patches) {
      if (p.surface != 0) continue;
      for (int k = 0; k < p.corner_count; ++k) {
        const Vec3 a = p.corners[k], c = p.corners[(k + 1) % p.corner_count];
        const double along = Dot(d.positions[v] - a, c - a) / Dot(c - a, c - a);
        if (along > 1e-9 && along < 1 - 1e-9 &&
            Length(d.positions[v] - (a + (c - a) * along)) < 1e-9) {
          ++t_vertices;
        }
      }
    }
  }
  EXPECT_GT(t_vertices, 0);
}

// A farm checkpoint keeps the refined PatchScene; the mesh for the outputs is rebuilt from it.
TEST(RefineTest, RefinedMeshRebuildsFromItsPatchScene) {
  Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  RefinedMesh refined = RefineBeforeShooting(*mesh, Settings(0.1, 0.0625, 100000));
  const PatchScene& a = refined.mesh.patch_scene();
  PatchMesh again = mesh->Rebuilt(PatchMesh::PiecesOf(a));
  const PatchScene& b = again.patch_scene();
  ASSERT_EQ(a.patches.size(), b.patches.size());
  for (size_t i = 0; i < a.patches.size(); ++i) {
    EXPECT_EQ(a.patches[i].corners, b.patches[i].corners);
    EXPECT_EQ(a.patches[i].area, b.patches[i].area);
    EXPECT_EQ(a.patches[i].surface, b.patches[i].surface);
  }
  std::vector<Rgb> values;
  for (size_t i = 0; i < a.patches.size(); ++i) values.push_back({double(i), 1, 2});
  const DisplayMesh da = testing::AveragedOf(refined.mesh, values);
  const DisplayMesh db = testing::AveragedOf(again, values);
  EXPECT_EQ(da.triangles, db.triangles);
  EXPECT_EQ(da.radiance, db.radiance);
}

// An open 2 x 2 x 2 box lit by its whole ceiling: smooth light everywhere.
InputScene SmoothRoom() {
  SceneBuilder s;
  s.AddMaterial("white", {0.6, 0.6, 0.6});
  s.AddMaterial("light", {0, 0, 0}, {1, 1, 1});
  s.AddFace({{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}}, 0);  // floor, up
  s.AddFace({{0, 0, 0}, {0, 2, 0}, {0, 2, 2}, {0, 0, 2}}, 0);  // x = 0, facing +x
  s.AddFace({{2, 0, 0}, {2, 0, 2}, {2, 2, 2}, {2, 2, 0}}, 0);  // x = 2, facing -x
  s.AddFace({{0, 2, 0}, {2, 2, 0}, {2, 2, 2}, {0, 2, 2}}, 1);  // ceiling light, down
  return s.scene();
}

TEST(RefineTest, RefinedAndUnrefinedAgreeOnSmoothLight) {
  SolverSettings settings;
  settings.shot_rays = 1 << 20;
  settings.tolerance = 1e-3;
  settings.threads = 2;
  RefineSettings refine;
  refine.enabled = true;
  refine.tolerance = 0.05;
  Result<PatchMesh> coarse = PatchMesh::Build(SmoothRoom(), {0.25}, nullptr);
  ASSERT_TRUE(coarse.ok());
  const SolveResult plain = Solve(coarse->patch_scene(), settings);
  Result<PatchMesh> start = PatchMesh::Build(SmoothRoom(), {0.25}, nullptr);
  Result<RefiningSolveResult> refined = SolveRefining(std::move(*start), settings, refine);
  ASSERT_TRUE(refined.ok());
  const PatchScene& fine = refined->mesh->patch_scene();
  ASSERT_GT(fine.patches.size(), coarse->patch_scene().patches.size());  // it did refine
  // Area-weighted average of the elements over each coarse patch, against the coarse solution.
  const std::vector<uint32_t> home = LocatePatchCentres(coarse->patch_scene(), fine);
  std::vector<double> sum(coarse->patch_scene().patches.size(), 0.0), area(sum.size(), 0.0);
  for (size_t i = 0; i < fine.patches.size(); ++i) {
    ASSERT_NE(home[i], kNoPatch);
    sum[home[i]] += fine.patches[i].area * refined->solution.radiosity[i].Sum();
    area[home[i]] += fine.patches[i].area;
  }
  double sq = 0;
  int n = 0;
  for (size_t j = 0; j < sum.size(); ++j) {
    if (coarse->patch_scene().patches[j].emission.Max() > 0) continue;
    EXPECT_NEAR(area[j], coarse->patch_scene().patches[j].area, 1e-9);
    const double rel = sum[j] / area[j] / plain.radiosity[j].Sum() - 1;
    sq += rel * rel;
    ++n;
  }
  // About a thousand rays reach each coarse patch per unit of emitted power shot: noise of a few
  // per cent per patch; a biased transfer (children not inheriting the parent's value, lost power)
  // shows as a systematic offset far above that.
  EXPECT_LT(std::sqrt(sq / n), 0.03);
  // Energy balance after refinement.
  const SolveStats& st = refined->solution.stats;
  EXPECT_NEAR(st.emitted_power,
              st.absorbed_power + st.escaped_power + st.unshot_fraction * st.emitted_power,
              1e-9 * st.emitted_power);
}

SolverSettings Deterministic(uint32_t threads) {
  SolverSettings s;
  s.shot_rays = 1 << 16;
  s.tolerance = 0.01;
  s.threads = threads;
  return s;
}

TEST(RefineTest, SameMeshAndSolutionOnAnyThreadCount) {
  RefineSettings refine;
  refine.enabled = true;
  refine.tolerance = 0.1;
  refine.min_element_size = 0.0625;
  std::vector<Result<RefiningSolveResult>> runs;
  for (uint32_t threads : {1u, 3u}) {
    Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
    ASSERT_TRUE(mesh.ok());
    runs.push_back(SolveRefining(std::move(*mesh), Deterministic(threads), refine));
    ASSERT_TRUE(runs.back().ok());
  }
  const PatchScene& a = runs[0]->mesh->patch_scene();
  const PatchScene& b = runs[1]->mesh->patch_scene();
  ASSERT_EQ(a.patches.size(), b.patches.size());
  EXPECT_GT(a.patches.size(), runs[0]->patches_before);
  for (size_t i = 0; i < a.patches.size(); ++i) {
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(a.patches[i].corners[k].x, b.patches[i].corners[k].x);
      EXPECT_EQ(a.patches[i].corners[k].z, b.patches[i].corners[k].z);
    }
  }
  EXPECT_EQ(runs[0]->solution.radiosity, runs[1]->solution.radiosity);
  EXPECT_EQ(runs[0]->solution.stats.rays, runs[1]->solution.stats.rays);
}

TEST(RefineTest, DisabledIsSolveBitForBit) {
  Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  const SolveResult plain = Solve(mesh->patch_scene(), Deterministic(2));
  Result<RefiningSolveResult> off = SolveRefining(std::move(*mesh), Deterministic(2), {});
  ASSERT_TRUE(off.ok());
  EXPECT_EQ(off->patches_before, off->mesh->patch_scene().patches.size());
  EXPECT_EQ(off->solution.radiosity, plain.radiosity);
  EXPECT_EQ(off->solution.unshot, plain.unshot);
}

TEST(RefineTest, SettingsOutOfRangeNameTheKey) {
  RefineSettings bad;
  bad.enabled = true;
  bad.min_element_size = 1e-9;
  Result<ResolvedRefineSettings> r =
      ResolveRefineSettings(bad, 0.5, 100, 1e-6, PhysicalMemoryBytes());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("mesh.min_element_size"), std::string::npos) << r.error();
  RefineSettings automatic;
  Result<ResolvedRefineSettings> a =
      ResolveRefineSettings(automatic, 0.5, 100, 1e-6, PhysicalMemoryBytes());
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->min_element_size, 0.5 / 4);
  EXPECT_EQ(a->max_elements, 800u);
}

// The automatic element budget stops at what the memory limit holds.
TEST(RefineTest, TheAutomaticElementBudgetFitsInTheMemoryLimit) {
  const uint64_t memory = kSolveBaseBytes + 100000 * kSolveBytesPerPatch;
  const uint64_t fit = 100000;
  EXPECT_EQ(AutomaticElementBudget(100, memory), 800u);
  EXPECT_EQ(AutomaticElementBudget(fit / 4, memory), fit);      // 8 x would be twice the memory
  EXPECT_EQ(AutomaticElementBudget(fit * 2, memory), fit * 2);  // never below the initial patches
  RefineSettings automatic;
  Result<ResolvedRefineSettings> r = ResolveRefineSettings(automatic, 0.5, fit / 4, 1e-6, memory);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->max_elements, fit);
}

// A mesh built under --max-memory (MeshSettings::max_memory) carries the limit to refinement's
// budget; without one, this machine's memory.
TEST(RefineTest, TheMeshCarriesItsMemoryLimitToRefinement) {
  const InputScene scene = OccluderScene();
  MeshSettings settings;
  settings.patch_size = 0.5;
  Result<PatchMesh> unlimited = PatchMesh::Build(scene, settings, nullptr);
  ASSERT_TRUE(unlimited.ok()) << unlimited.error();
  EXPECT_EQ(unlimited->memory_limit(), PhysicalMemoryBytes());
  settings.max_memory = kSolveBaseBytes + 1000 * kSolveBytesPerPatch;
  Result<PatchMesh> limited = PatchMesh::Build(scene, settings, nullptr);
  ASSERT_TRUE(limited.ok()) << limited.error();
  EXPECT_EQ(limited->memory_limit(), settings.max_memory);
  EXPECT_EQ(limited->Rebuilt(PatchMesh::PiecesOf(limited->patch_scene())).memory_limit(),
            settings.max_memory);
  Result<MeshCheck> check = PatchMesh::Check(scene, settings, nullptr);
  ASSERT_TRUE(check.ok()) << check.error();
  EXPECT_EQ(check->memory_limit, settings.max_memory);
}

}  // namespace
}  // namespace radfarm
