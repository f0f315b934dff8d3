// core/light_tree.h and DirectLight's many-light path: the bounds never fall below a
// light's true unoccluded irradiance, the sampled estimate averages to the exact sum, it is the
// same whatever the threads, and up to kExactLights lights the exact sum is kept to the bit.
#include "core/light_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/counter_rng.h"
#include "core/direct_light.h"
#include "core/point_form_factor.h"
#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::BitIdentical;

constexpr size_t kNoTree = std::numeric_limits<size_t>::max();

double U(uint64_t seed, uint64_t i, uint32_t dim) {
  return CounterRng(HashWords(seed, i)).Uniform(dim);
}

// A grey 10 x 10 floor at z = 0 facing up, and `count` square panels (2 x 2 patches, 0.4 m, one
// surface each) scattered 1 to 4 m above it, facing down at up to about 60 degrees off vertical,
// of random emission. With `occluder`, an opaque sheet at z = 0.5 over x < 0.
PatchScene ManyPanels(int count, uint64_t seed, bool occluder) {
  PatchScene scene;
  testing::AddQuadGrid({-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}, 4,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 0}, &scene);
  if (occluder) {
    testing::AddQuadGrid({-5, -5, 0.5}, {0, -5, 0.5}, {0, 5, 0.5}, {-5, 5, 0.5}, 2,
                         testing::Surface{{0.5, 0.5, 0.5}, {}, 1}, &scene);
  }
  for (int i = 0; i < count; ++i) {
    const Vec3 c{10 * U(seed, i, 0) - 5, 10 * U(seed, i, 1) - 5, 1 + 3 * U(seed, i, 2)};
    const Vec3 normal = Normalize({U(seed, i, 3) - 0.5, U(seed, i, 4) - 0.5, -1});
    Vec3 t, b;
    OrthonormalBasis(normal, &t, &b);
    const double h = 0.2;
    const Rgb ke{1 + 4 * U(seed, i, 5), 1 + 4 * U(seed, i, 6), 1 + 4 * U(seed, i, 7)};
    testing::AddQuadGrid(c - t * h - b * h, c + t * h - b * h, c + t * h + b * h, c - t * h + b * h,
                         2, testing::Surface{{0.5, 0.5, 0.5}, ke, uint32_t(2 + i)}, &scene);
  }
  return scene;
}

// Receivers on the floor, and some in the air facing every way.
std::vector<ReceiverPoint> Receivers(int count, uint64_t seed) {
  std::vector<ReceiverPoint> points;
  for (int i = 0; i < count; ++i) {
    const Vec3 x{9 * U(seed, i, 0) - 4.5, 9 * U(seed, i, 1) - 4.5, 0};
    if (i % 4 != 3) {
      points.push_back({x, {0, 0, 1}});
    } else {
      const Vec3 n = Normalize({U(seed, i, 2) - 0.5, U(seed, i, 3) - 0.5, U(seed, i, 4) - 0.5});
      points.push_back({x + Vec3{0, 0, 0.2 + 4 * U(seed, i, 5)}, n});
    }
  }
  return points;
}

// Every light's exact unoccluded irradiance (channel sum) at a point.
std::vector<double> TrueIrradiance(const std::vector<std::vector<const Patch*>>& lights,
                                   const Vec3& x, const Vec3& n) {
  std::vector<double> e;
  for (const auto& light : lights) {
    double sum = 0;
    for (const Patch* p : light) sum += p->emission.Sum() * PointToPatchFormFactor(x, n, *p);
    e.push_back(sum);
  }
  return e;
}

// Checks node's bound against the sum under it; returns that sum.
double CheckNode(const LightTree& tree, uint32_t node, const std::vector<double>& truth,
                 const Vec3& x, const Vec3& n, std::vector<uint32_t>* leaf_light) {
  const auto [left, right] = tree.Children(node);
  double sum;
  if (left == 0) {
    sum = truth[(*leaf_light)[node]];
  } else {
    sum = CheckNode(tree, left, truth, x, n, leaf_light) +
          CheckNode(tree, right, truth, x, n, leaf_light);
  }
  EXPECT_GE(tree.Bound(node, x, n), sum * (1 - 1e-12)) << "node " << node;
  return sum;
}

TEST(LightTreeTest, BoundsAreNeverBelowTheUnoccludedIrradiance) {
  const PatchScene scene = ManyPanels(300, 5, false);
  std::vector<std::vector<const Patch*>> lights(300);
  for (const Patch& p : scene.patches) {
    if (p.surface >= 2) lights[p.surface - 2].push_back(&p);
  }
  std::vector<LightBounds> bounds;
  for (const auto& light : lights) bounds.push_back(EmitterLightBounds(light, true));
  const LightTree tree(bounds);
  ASSERT_EQ(tree.size(), 2 * lights.size() - 1);
  std::vector<uint32_t> leaf_light(tree.size());
  for (uint32_t i = 0; i < lights.size(); ++i) leaf_light[tree.LeafOf(i)] = i;
  int lit = 0;
  for (const ReceiverPoint& r : Receivers(200, 9)) {
    const std::vector<double> truth = TrueIrradiance(lights, r.position, r.normal);
    lit += CheckNode(tree, 0, truth, r.position, r.normal, &leaf_light) > 0;
  }
  EXPECT_GT(lit, 150) << "the check must see light";
}

TEST(LightTreeTest, PointLightBoundsAreNeverBelowTheirIrradiance) {
  std::vector<PunctualLight> lamps;
  for (int i = 0; i < 100; ++i) {
    PunctualLight l;
    l.kind = i % 3 == 0 ? PunctualKind::kSpot : PunctualKind::kPoint;
    l.position = {10 * U(2, i, 0) - 5, 10 * U(2, i, 1) - 5, 3 * U(2, i, 2) - 1};
    l.direction = {0, 0, -1};
    l.intensity = {10 * U(2, i, 3), 10 * U(2, i, 4), 10 * U(2, i, 5)};
    lamps.push_back(l);
  }
  std::vector<LightBounds> bounds;
  for (const PunctualLight& l : lamps) bounds.push_back(PunctualLightBounds(l));
  const LightTree tree(bounds);
  std::vector<uint32_t> leaf_light(tree.size());
  for (uint32_t i = 0; i < lamps.size(); ++i) leaf_light[tree.LeafOf(i)] = i;
  for (const ReceiverPoint& r : Receivers(200, 4)) {
    std::vector<double> truth;
    for (const PunctualLight& l : lamps) {
      truth.push_back(UnshadowedIrradiance(l, r.position, r.normal).Sum());
    }
    CheckNode(tree, 0, truth, r.position, r.normal, &leaf_light);
  }
}

// Up to kExactLights lights, every light is evaluated and the sum is the one without a tree, to
// the bit; one more and the tree picks at most kLightCut.
TEST(LightTreeTest, FewLightsKeepTheExactSum) {
  for (const size_t count : {kExactLights, kExactLights + 1}) {
    const PatchScene scene = ManyPanels(int(count), 3, true);
    const RayCaster caster(scene);
    const DirectLight direct(scene, caster, kPointShadowRays);
    const DirectLight exact(scene, caster, kPointShadowRays, true, kNoTree);
    EXPECT_EQ(direct.emitter_lights(), count);
    EXPECT_EQ(direct.emitters_sampled(), count > kExactLights) << count;
    uint64_t key = 0;
    for (const ReceiverPoint& r : Receivers(50, 7)) {
      uint32_t evaluated = 0;
      const Rgb e = direct.EmitterIrradiance(r.position, r.normal, ++key, &evaluated);
      if (count <= kExactLights) {
        EXPECT_EQ(evaluated, count);
        EXPECT_TRUE(BitIdentical(std::vector<Rgb>{e},
                                 {exact.EmitterIrradiance(r.position, r.normal, key)}));
      } else {
        EXPECT_LE(evaluated, kLightCut);
      }
    }
  }
}

// Mean and standard error of the channel sums of `samples`.
std::pair<double, double> MeanAndError(const std::vector<double>& samples) {
  double sum = 0, sum2 = 0;
  for (double s : samples) sum += s, sum2 += s * s;
  const double n = double(samples.size()), mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1))};
}

// The sampled estimate's mean over keys against the exact sum's, at each point: within five
// standard errors (the exact sum varies with the key only through its shadow rays).
void ExpectUnbiased(const PatchScene& scene, bool occluder) {
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster, kPointShadowRays);
  const DirectLight exact(scene, caster, kPointShadowRays, true, kNoTree);
  ASSERT_TRUE(direct.emitters_sampled());
  for (const ReceiverPoint& r : Receivers(8, 21)) {
    std::vector<double> sampled, summed;
    for (uint64_t key = 0; key < 600; ++key) {
      sampled.push_back(direct.Irradiance(r.position, r.normal, key).Sum());
      summed.push_back(exact.Irradiance(r.position, r.normal, key).Sum());
    }
    const auto [ms, es] = MeanAndError(sampled);
    const auto [mx, ex] = MeanAndError(summed);
    EXPECT_NEAR(ms, mx, 5 * std::hypot(es, ex) + 1e-12 * mx)
        << "occluder " << occluder << " at " << r.position.x << " " << r.position.y << " "
        << r.position.z;
  }
}

TEST(LightTreeTest, SampledEstimateAveragesToTheExactSum) {
  ExpectUnbiased(ManyPanels(200, 11, false), false);
  ExpectUnbiased(ManyPanels(200, 12, true), true);
}

TEST(LightTreeTest, ManyPointLightsAverageToTheExactSum) {
  PatchScene scene = ManyPanels(0, 1, true);
  for (int i = 0; i < 200; ++i) {
    PunctualLight l;
    l.position = {10 * U(8, i, 0) - 5, 10 * U(8, i, 1) - 5, 1 + 3 * U(8, i, 2)};
    l.direction = {0, 0, -1};
    l.intensity = {1 + 9 * U(8, i, 3), 5, 5};
    scene.lights.push_back(l);
  }
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster, kPointShadowRays);
  const DirectLight exact(scene, caster, kPointShadowRays, true, kNoTree);
  for (const ReceiverPoint& r : Receivers(8, 22)) {
    const double want = exact.PunctualIrradiance(r.position, r.normal).Sum();
    std::vector<double> sampled;
    for (uint64_t key = 0; key < 600; ++key) {
      sampled.push_back(direct.PunctualIrradiance(r.position, r.normal, key).Sum());
    }
    const auto [mean, error] = MeanAndError(sampled);
    EXPECT_NEAR(mean, want, 5 * error + 1e-12 * want);
  }
}

// Whatever the threads, the same picks and the same values; and a different seed picks others.
TEST(LightTreeTest, SampledPointsIgnoreThreads) {
  const PatchScene scene = ManyPanels(500, 13, true);
  const std::vector<ReceiverPoint> points = Receivers(64, 3);
  const std::vector<Rgb> one = PointsDirectLight(scene, points, 7, 1);
  const std::vector<Rgb> three = PointsDirectLight(scene, points, 7, 3);
  EXPECT_TRUE(BitIdentical(one, three));
  EXPECT_FALSE(BitIdentical(one, PointsDirectLight(scene, points, 8, 3)));
}

// The solver's start with many emitters and many lamps, both sampled: the same whatever the
// threads.
TEST(LightTreeTest, SampledPatchDirectLightIgnoresThreads) {
  PatchScene scene = ManyPanels(100, 14, true);
  for (int i = 0; i < 100; ++i) {
    PunctualLight l;
    l.position = {10 * U(15, i, 0) - 5, 10 * U(15, i, 1) - 5, 1 + 3 * U(15, i, 2)};
    l.direction = {0, 0, -1};
    l.intensity = {2, 2, 2};
    scene.lights.push_back(l);
  }
  double power_one = 0, power_three = 0;
  const std::vector<Rgb> one = PatchDirectLight(scene, 4, 11, 1, true, &power_one);
  const std::vector<Rgb> three = PatchDirectLight(scene, 4, 11, 3, true, &power_three);
  EXPECT_TRUE(BitIdentical(one, three));
  EXPECT_EQ(power_one, power_three);
  EXPECT_GT(power_one, 0);
}

}  // namespace
}  // namespace radfarm
