// output/illuminance_light.h against closed forms: a lamp over an open floor (E = I cos / r^2 and
// nothing else) and a closed furnace (every direction sees the radiosity B: E = pi B), and the
// same bits on any number of threads.
#include "output/illuminance_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::AddQuadGrid;
using testing::BitIdentical;
using testing::Gathering;
using testing::MakeClosedBox;
using testing::Surface;

constexpr double kPi = std::numbers::pi;

TEST(IlluminanceLightTest, LuxIsPiTimesTheLuminanceOfTheIrradiance) {
  EXPECT_DOUBLE_EQ(LuxOf({1, 1, 1}), kPi);
  EXPECT_DOUBLE_EQ(LuxOf({0, 1, 0}), kPi * 0.7152);
  EXPECT_EQ(LuxOf({}), 0);
}

std::vector<double> Lux(const PatchScene& scene, const std::vector<Rgb>& radiosity,
                        const SolverSettings& solver, const std::vector<ReceiverPoint>& points) {
  const RayCaster caster(scene);
  const std::vector<Rgb> no_start;
  std::vector<double> lux;
  for (const Rgb& e : IrradianceAtPoints({scene, caster, radiosity, no_start, solver}, points)) {
    lux.push_back(LuxOf(e));
  }
  return lux;
}

// A lamp of 100 cd 2 m over an open grey floor: a point facing up sees no surface, only the lamp.
TEST(IlluminanceLightTest, ALampOverAnOpenFloorGivesIntensityTimesCosineOverDistanceSquared) {
  PatchScene scene;
  AddQuadGrid({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, 4, Surface{{0.5, 0.5, 0.5}, {}, 0},
              &scene);
  PunctualLight lamp;
  lamp.position = {0, 2, 0};
  lamp.intensity = {100, 100, 100};
  scene.lights.push_back(lamp);
  const std::vector<Rgb> radiosity(scene.patches.size());
  const std::vector<ReceiverPoint> points = {
      {{0, 0.8, 0}, {0, 1, 0}}, {{1, 0.8, 0.5}, {0, 1, 0}}, {{2, 0.8, -1.5}, {0, 1, 0}}};
  const std::vector<double> lux = Lux(scene, radiosity, Gathering(256), points);
  ASSERT_EQ(lux.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 to = lamp.position - points[i].position;
    const double r = Length(to);
    const double expected = 100 * (to.y / r) / (r * r);
    EXPECT_NEAR(lux[i], expected, 1e-9 * expected) << i;
  }
}

// Every surface of a closed box emits 1 and reflects half: B = 1 / (1 - 0.5) = 2 everywhere, so a
// point anywhere inside receives pi B = 2 pi lux. Without the gather the emitters shoot and the
// point gathers B from every ray: exact to rounding. With it, the emitters are in the direct light
// at the point (form factors in closed form, visibility by shadow rays, a few of which graze the
// box's edges and miss) and the point gathers the rest: to a thousandth.
TEST(IlluminanceLightTest, AClosedFurnaceGivesPiTimesItsRadiosity) {
  const PatchScene scene =
      MakeClosedBox({0, 0, 0}, {4, 3, 4}, 2, Surface{{0.5, 0.5, 0.5}, {1, 1, 1}, 0});
  const std::vector<Rgb> radiosity(scene.patches.size(), Rgb{2, 2, 2});
  const std::vector<ReceiverPoint> points = {
      {{1, 0.8, 1}, {0, 1, 0}}, {{2, 1.5, 2}, {0, 1, 0}}, {{3.9, 0.1, 0.1}, {0, 1, 0}}};
  const std::vector<double> shot = Lux(scene, radiosity, SolverSettings{}, points);
  const std::vector<double> started = Lux(scene, radiosity, Gathering(2048), points);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(shot[i], 2 * kPi, 1e-9) << i;
    EXPECT_NEAR(started[i], 2 * kPi, 1e-3 * 2 * kPi) << i;
  }
}

TEST(IlluminanceLightTest, TheSameBitsOnAnyNumberOfThreads) {
  const PatchScene scene = testing::LitBox();
  std::vector<Rgb> radiosity(scene.patches.size());
  for (size_t f = 0; f < radiosity.size(); ++f) radiosity[f] = Rgb{0.1, 0.2, 0.3} * double(f % 7);
  std::vector<ReceiverPoint> points;
  for (int k = 0; k < 20; ++k) points.push_back({{0.05 + 0.045 * k, 0.3, 0.5}, {0, 1, 0}});
  SolverSettings one = Gathering(512), two = Gathering(512);
  one.threads = 1;
  two.threads = 2;
  const RayCaster caster(scene);
  const std::vector<Rgb> no_start;
  uint64_t rays_one = 0, rays_two = 0;
  const std::vector<Rgb> a =
      IrradianceAtPoints({scene, caster, radiosity, no_start, one}, points, &rays_one);
  const std::vector<Rgb> b =
      IrradianceAtPoints({scene, caster, radiosity, no_start, two}, points, &rays_two);
  EXPECT_TRUE(BitIdentical(a, b));
  EXPECT_EQ(rays_one, rays_two);
  EXPECT_GT(rays_one, points.size() * kIlluminanceGatherRays);
}

}  // namespace
}  // namespace radfarm
