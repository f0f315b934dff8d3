// core/punctual_light.h and its part in core/direct_light.h and the solver's start: points, spots
// and suns against glTF's closed forms, their shadows, and a scene lit by them alone.
#include "core/punctual_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/back_face_survey.h"
#include "core/direct_light.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::BitIdentical;
using testing::Gathering;

constexpr double kPi = std::numbers::pi;

// A grey 4 x 4 floor [-2, 2]^2 at z = 0, facing up, and the given lights.
PatchScene LampFloor(std::vector<PunctualLight> lights) {
  PatchScene scene;
  testing::AddQuadGrid({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, 4,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 0}, &scene);
  scene.lights = std::move(lights);
  return scene;
}

PunctualLight PointLamp(const Vec3& at, const Rgb& candela) {
  PunctualLight l;
  l.kind = PunctualKind::kPoint;
  l.position = at;
  l.direction = {0, 0, -1};
  l.intensity = candela;
  return l;
}

// The solver's units are lux / pi (core/punctual_light.h): times pi, lux.
Rgb Lux(const std::vector<Rgb>& e, size_t i) { return e[i] * kPi; }

TEST(PunctualLightTest, PointLightGivesInverseSquareCosineIrradiance) {
  const PatchScene scene = LampFloor({PointLamp({0.3, -0.2, 1.5}, {100, 50, 10})});
  const std::vector<ReceiverPoint> points = {
      {{0.3, -0.2, 0}, {0, 0, 1}},  // straight below: I / d^2
      {{1.3, 0.8, 0}, {0, 0, 1}},   // off to the side
      {{-1.7, 1.1, 0}, {0, 0, 1}},
  };
  const std::vector<Rgb> e = PointsDirectLight(scene, points, 3, 2);
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = Vec3{0.3, -0.2, 1.5} - points[i].position;
    const double r2 = Dot(d, d), cos_theta = d.z / std::sqrt(r2);
    EXPECT_NEAR(Lux(e, i).r, 100 * cos_theta / r2, 1e-9 * 100 / r2) << i;
    EXPECT_NEAR(Lux(e, i).g, 50 * cos_theta / r2, 1e-9 * 50 / r2) << i;
    EXPECT_NEAR(Lux(e, i).b, 10 * cos_theta / r2, 1e-9 * 10 / r2) << i;
  }
  EXPECT_NEAR(Lux(e, 0).r, 100 / (1.5 * 1.5), 1e-9);
}

TEST(PunctualLightTest, NothingBehindTheSurfaceOrAtTheLight) {
  const PunctualLight lamp = PointLamp({0, 0, 1}, {1, 1, 1});
  EXPECT_EQ(UnshadowedIrradiance(lamp, {0, 0, 0}, {0, 0, -1}), Rgb{});
  EXPECT_EQ(UnshadowedIrradiance(lamp, {0, 0, 1}, {0, 0, 1}), Rgb{});
}

TEST(PunctualLightTest, RangeFadesToZeroAsGltfRecommends) {
  PunctualLight lamp = PointLamp({0, 0, 2}, {1, 1, 1});
  lamp.range = 4;
  // d = 2 of 4: window 1 - (1/2)^4.
  EXPECT_NEAR(UnshadowedIrradiance(lamp, {0, 0, 0}, {0, 0, 1}).r * kPi, (1 - 1.0 / 16) / 4, 1e-12);
  lamp.range = 2;
  EXPECT_EQ(UnshadowedIrradiance(lamp, {0, 0, 0}, {0, 0, 1}), Rgb{}) << "at the range: nothing";
  lamp.range = 1;
  EXPECT_EQ(UnshadowedIrradiance(lamp, {0, 0, 0}, {0, 0, 1}), Rgb{}) << "beyond it";
}

TEST(PunctualLightTest, SpotConeIsFullInsideZeroOutsideAndSmoothBetween) {
  PunctualLight spot = PointLamp({0, 0, 1}, {10, 10, 10});
  spot.kind = PunctualKind::kSpot;
  spot.direction = {0, 0, -1};
  spot.inner_cone = 0.2;
  spot.outer_cone = 0.6;
  const PatchScene scene = LampFloor({spot});
  // Floor points at angle a off the axis: x = tan(a) at height 1.
  const double mid_cos = (std::cos(0.2) + std::cos(0.6)) / 2;  // ramp 1/2: falloff 1/4
  const double mid = std::acos(mid_cos);
  const std::vector<double> angles = {0.0, 0.15, mid, 0.65, 1.0};
  std::vector<ReceiverPoint> points;
  for (double a : angles) points.push_back({{std::tan(a), 0, 0}, {0, 0, 1}});
  const std::vector<Rgb> e = PointsDirectLight(scene, points, 3, 1);
  const auto unshadowed = [](double a) {
    const double d2 = 1 + std::tan(a) * std::tan(a);
    return 10 * std::cos(a) / d2;  // I cos(theta) / d^2, theta = a on a floor under the lamp
  };
  EXPECT_NEAR(Lux(e, 0).g, unshadowed(0), 1e-9) << "on the axis";
  EXPECT_NEAR(Lux(e, 1).g, unshadowed(0.15), 1e-9) << "inside the inner cone";
  EXPECT_NEAR(Lux(e, 2).g, 0.25 * unshadowed(mid), 1e-9) << "half way in cosine";
  EXPECT_EQ(e[3], Rgb{}) << "just outside the outer cone";
  EXPECT_EQ(e[4], Rgb{});
  EXPECT_EQ(SpotFalloff(spot, std::cos(0.6)), 0.0);
  EXPECT_EQ(SpotFalloff(spot, std::cos(0.2)), 1.0);
  // Monotone from the inner to the outer cone.
  double last = 1;
  for (double a = 0.2; a <= 0.6; a += 0.01) {
    const double f = SpotFalloff(spot, std::cos(a));
    EXPECT_LE(f, last + 1e-15) << a;
    last = f;
  }
}

TEST(PunctualLightTest, SunGivesLuxTimesCosine) {
  PunctualLight sun;
  sun.kind = PunctualKind::kSun;
  sun.direction = Normalize(Vec3{1, 0, -2});  // travelling down and toward +x
  sun.intensity = {1000, 800, 600};
  const PatchScene scene = LampFloor({sun});
  const std::vector<Rgb> e =
      PointsDirectLight(scene, {{{0, 0, 0}, {0, 0, 1}}, {{1.5, -1.5, 0}, {0, 0, 1}}}, 3, 2);
  const double cos_theta = 2 / std::sqrt(5.0);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(Lux(e, i).r, 1000 * cos_theta, 1e-9) << i;
    EXPECT_NEAR(Lux(e, i).b, 600 * cos_theta, 1e-9) << i;
  }
}

TEST(PunctualLightTest, ABlockerCastsAShadowOfEachKind) {
  PunctualLight sun;
  sun.kind = PunctualKind::kSun;
  sun.direction = {0, 0, -1};
  sun.intensity = {5, 5, 5};
  PunctualLight spot = PointLamp({0, 0, 3}, {20, 20, 20});
  spot.kind = PunctualKind::kSpot;
  for (const PunctualLight& light : {PointLamp({0, 0, 3}, {20, 20, 20}), spot, sun}) {
    PatchScene scene = LampFloor({light});
    // A small board at z = 1 over [-0.5, 0.5]^2, facing up (shadows need no front face).
    testing::AddQuadGrid({-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1}, 1,
                         testing::Surface{{0.5, 0.5, 0.5}, {}, 1}, &scene);
    const std::vector<Rgb> e =
        PointsDirectLight(scene, {{{0.1, 0.1, 0}, {0, 0, 1}}, {{1.2, 0, 0}, {0, 0, 1}}}, 3, 2);
    EXPECT_EQ(e[0], Rgb{}) << "under the board, kind " << int(light.kind);
    EXPECT_GT(e[1].r, 0) << "beside it, kind " << int(light.kind);
  }
}

TEST(PunctualLightTest, PatchAverageMatchesTheClosedFormAndIgnoresThreads) {
  // A lamp high above a small patch: the average over it is close to the value at its centre.
  const PatchScene scene = LampFloor({PointLamp({-1.5, -1.5, 20}, {400, 400, 400})});
  const std::vector<Rgb> one = PatchDirectLight(scene, 8, 11, 1, false);
  const std::vector<Rgb> three = PatchDirectLight(scene, 8, 11, 3, false);
  EXPECT_TRUE(BitIdentical(one, three));
  // Patch 0: [-2, -1]^2, centre (-1.5, -1.5): 400 / 400 = 1 lux, within 1e-3.
  EXPECT_NEAR(one[0].g * kPi, 1.0, 1e-3);
  double power = -1;
  PatchDirectLight(scene, 8, 11, 2, false, &power);
  double sum = 0;
  for (size_t i = 0; i < one.size(); ++i) sum += scene.patches[i].area * one[i].Sum();
  EXPECT_DOUBLE_EQ(power, sum);
}

TEST(PunctualLightTest, SectionsCountLightsAndNeedNoGather) {
  PatchScene scene = LampFloor({PointLamp({0, 0, 1}, {1, 1, 1})});
  EXPECT_EQ(DirectLightSections(scene, Gathering(0)), 16u) << "512 rays without a gather";
  EXPECT_EQ(DirectLightSections(scene, Gathering(64)), 5u) << "floor(sqrt(64 / 2))";
  EXPECT_FALSE(EmittersInDirectStart(scene, Gathering(2048)));
  scene.lights.clear();
  EXPECT_EQ(DirectLightSections(scene, Gathering(2048)), 0u);
}

// A closed box lit by a point lamp alone: the solve starts from the lamp's light, its account
// balances, and it converges as a box with an emitter does; with any number of threads.
TEST(PunctualLightTest, ABoxLitByALampAloneSolvesWithAndWithoutGather) {
  PatchScene scene =
      testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 4, testing::Surface{{0.6, 0.6, 0.6}, {}, 0});
  scene.lights = {PointLamp({0.5, 0.8, 0.5}, {1, 1, 1})};
  for (uint32_t gather_rays : {0u, 256u}) {
    SolverSettings settings = Gathering(gather_rays, 2000);
    ProgressiveSolver solver(scene, settings);
    ASSERT_EQ(solver.direct_light().size(), scene.patches.size()) << gather_rays;
    const EnergyAccount& start = solver.energy();
    // A closed box takes all of a point lamp's power, 4 pi I lm, in units of lux / pi: 4 I per
    // channel, 12 in all; the patch averages of 8 x 8 points come within a percent.
    EXPECT_NEAR(start.emitted, 12.0, 0.12) << gather_rays;
    EXPECT_NEAR(start.emitted, start.absorbed + solver.SignedUnshotPower() + start.escaped, 1e-9);
    EXPECT_GT(solver.UnshotFraction(), 0.5);
    settings.threads = 1;
    ProgressiveSolver single(scene, settings);
    EXPECT_TRUE(BitIdentical(solver.direct_light(), single.direct_light()));
  }
}

// Emitter patches that shoot (no gather) beside a lamp in the start: both lights are counted once.
TEST(PunctualLightTest, EmittersStillShootBesideALampWithoutGather) {
  PatchScene scene = testing::LitBox();
  scene.lights = {PointLamp({0.5, 0.5, 0.5}, {1, 1, 1})};
  const ProgressiveSolver solver(scene, Gathering(0, 2000));
  const std::vector<Rgb>& direct = solver.direct_light();
  ASSERT_FALSE(direct.empty());
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    EXPECT_EQ(solver.unshot()[i], p.emission + p.reflectance * direct[i]) << i;
  }
  const EnergyAccount& e = solver.energy();
  EXPECT_NEAR(e.emitted, e.absorbed + solver.SignedUnshotPower() + e.escaped, 1e-9);
}

// The survey behind "lit from behind" (core/back_face_survey.h) shoots from lamps too: a lamp in
// a box of inward faces meets fronts only, the same lamp outside meets backs only, a sun nothing.
TEST(PunctualLightTest, TheBackFaceSurveyShootsFromPointAndSpotLamps) {
  PatchScene box =
      testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 2, testing::Surface{{0.5, 0.5, 0.5}, {}, 0});
  box.material_names = {"wall"};
  PunctualLight spot = PointLamp({0.5, 0.5, 0.5}, {1, 1, 1});
  spot.kind = PunctualKind::kSpot;
  for (const PunctualLight& inside : {PointLamp({0.5, 0.5, 0.5}, {1, 1, 1}), spot}) {
    PatchScene scene = box;
    scene.lights = {inside};
    const RayCaster caster(scene);
    const BackFaceCounts counts = SurveyBackFaces(scene, caster, 1000);
    EXPECT_EQ(counts.rays, 1000u);
    EXPECT_EQ(counts.front[0], 1000u);
    EXPECT_EQ(counts.back[0], 0u);
  }
  PatchScene scene = box;
  scene.lights = {PointLamp({0.5, 3, 0.5}, {1, 1, 1})};
  const RayCaster caster(scene);
  const BackFaceCounts outside = SurveyBackFaces(scene, caster, 10000);
  EXPECT_EQ(outside.front[0], 0u);
  // The box's top, 2 below the lamp, subtends 4 atan(1 / (4 sqrt(18))) = 0.2352 sr: 1.87% of the
  // sphere, 187 rays; within 3.5 standard deviations (13.6).
  EXPECT_NEAR(double(outside.back[0]), 187.2, 48);
  PunctualLight sun;
  sun.kind = PunctualKind::kSun;
  sun.direction = {0, -1, 0};
  sun.intensity = {1, 1, 1};
  scene.lights = {sun};
  EXPECT_EQ(SurveyBackFaces(scene, caster, 1000).rays, 0u);
}

}  // namespace
}  // namespace radfarm
