// A refinement step's light scores traced in pieces, on any threads and on a caster of their own,
// are the bits Refine computes itself, and a Refine whose scores come from elsewhere makes the
// same mesh.
#include "mesh/light_scores.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/ray_caster.h"
#include "core/thread_pool.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::OccluderScene;

// The work of scoring every patch of `scene` against its emitters, as before the first round.
LightScoreWork EveryPatch(const PatchScene& scene) {
  std::vector<Rgb> unshot;
  for (const Patch& p : scene.patches) unshot.push_back(p.emission);
  LightScoreWork work{StrongestSources(scene, unshot, kLightSources), 0.1, {}};
  for (const Patch& p : scene.patches) {
    work.elements.push_back({p, p.reflectance, p.surface, p.emission});
  }
  return work;
}

TEST(LightScoresTest, PiecesOnAnyThreadsAndCastersGiveLightScoresBits) {
  Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  const PatchScene& scene = mesh->patch_scene();
  const LightScoreWork work = EveryPatch(scene);
  ASSERT_FALSE(work.sources.empty());
  const std::vector<uint32_t> surface_of = SurfacesOf(scene);
  const RayCaster caster(scene);
  std::vector<double> expected;
  for (const Patch& p : scene.patches) {
    expected.push_back(LightScore(p, p.emission, work.sources, surface_of, caster, 0.1));
  }
  ThreadPool one(1);
  EXPECT_EQ(TraceLightScores(work, surface_of, caster, 0, work.elements.size(), one), expected);
  // Pieces of odd sizes on three threads, against a caster built again as an agent builds one.
  const RayCaster elsewhere(scene);
  ThreadPool three(3);
  std::vector<double> pieced;
  for (size_t begin = 0; begin < work.elements.size(); begin += 37) {
    const size_t end = std::min(work.elements.size(), begin + 37);
    const std::vector<double> piece =
        TraceLightScores(work, surface_of, elsewhere, begin, end, three);
    pieced.insert(pieced.end(), piece.begin(), piece.end());
  }
  EXPECT_EQ(pieced, expected);
  size_t above = 0;
  for (double s : expected) above += s > 1;
  EXPECT_GT(above, 0u) << "the occluder's penumbra asks for splits";
}

TEST(LightScoresTest, RefineWithScoresTracedElsewhereMakesTheSameMesh) {
  const ResolvedRefineSettings settings{0.1, 0.0625, 100000};
  auto refine = [&](const LightScoreSource& source) {
    Result<PatchMesh> mesh = PatchMesh::Build(OccluderScene(), {0.5}, nullptr);
    EXPECT_TRUE(mesh.ok());
    std::vector<Rgb> b;
    for (const Patch& p : mesh->patch_scene().patches) b.push_back(p.emission);
    const RayCaster caster(mesh->patch_scene());
    ThreadPool pool(2);
    return Refine(*mesh, b, b, 0, settings, caster, pool, source);
  };
  const RefinedMesh here = refine({});
  size_t asked = 0, elements = 0;
  // As the farm's agents do: the scene's own caster, pieces of 50 elements, one thread.
  const RefinedMesh elsewhere = refine([&](const PatchScene& scene, const LightScoreWork& work) {
    ++asked;
    elements += work.elements.size();
    const RayCaster caster(scene);
    const std::vector<uint32_t> surface_of = SurfacesOf(scene);
    ThreadPool one(1);
    std::vector<double> scores;
    for (size_t begin = 0; begin < work.elements.size(); begin += 50) {
      const size_t end = std::min(work.elements.size(), begin + 50);
      const std::vector<double> piece = TraceLightScores(work, surface_of, caster, begin, end, one);
      scores.insert(scores.end(), piece.begin(), piece.end());
    }
    return std::optional<std::vector<double>>(std::move(scores));
  });
  // A source that declines every time leaves the scoring to Refine's pool.
  const RefinedMesh declined =
      refine([](const PatchScene&, const LightScoreWork&) { return std::nullopt; });
  EXPECT_GT(asked, 1u) << "the first pass and the children's";
  ASSERT_GT(here.split, 0u);
  for (const RefinedMesh* other : {&elsewhere, &declined}) {
    EXPECT_EQ(other->split, here.split);
    const auto& a = here.mesh.patch_scene().patches;
    const auto& b = other->mesh.patch_scene().patches;
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].corners, b[i].corners) << i;
    EXPECT_EQ(other->radiosity, here.radiosity);
  }
}

}  // namespace
}  // namespace radfarm
