// core/sky.h and the sky's part in the direct light (core/direct_light.h, core/direct_start.h):
// the CIE skies against their closed forms, an open floor under a uniform sky (E = pi L), a hole
// in a roof against its form factor, the energy account, and the start's pieces against the whole.
#include "core/sky.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/direct_light.h"
#include "core/direct_start.h"
#include "core/point_form_factor.h"
#include "core/ray_caster.h"
#include "core/solve_rules.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

constexpr double kPi = std::numbers::pi;

// A grey n x n floor [-2, 2]^2 at y = 0 facing up (+Y), under `sky`.
PatchScene OpenFloor(const Sky& sky, int n = 4) {
  PatchScene scene;
  testing::AddQuadGrid({-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, n,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 0}, &scene);
  scene.sky = sky;
  return scene;
}

// The dome's horizontal illuminance by another quadrature than SkyHorizontalIlluminance's:
// midpoints in (theta, phi), L cos sin dtheta dphi.
double HorizontalByThetaPhi(const Sky& sky) {
  constexpr int kTheta = 1500, kPhi = 1500;
  double sum = 0;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) * (kPi / 2) / kTheta;
    for (int j = 0; j < kPhi; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / kPhi;
      const Vec3 w{std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi)};
      sum += SkyLuminance(sky, w) * std::cos(theta) * std::sin(theta);
    }
  }
  return sum * (kPi / 2 / kTheta) * (2 * kPi / kPhi);
}

TEST(SkyTest, LuminanceFollowsTheCieFormulas) {
  const Sky overcast{SkyKind::kCieOvercast, 3000, {0, 1, 0}};
  EXPECT_DOUBLE_EQ(SkyLuminance(overcast, {0, 1, 0}), 3000);
  EXPECT_NEAR(SkyLuminance(overcast, Normalize(Vec3{1, 1e-9, 0})), 1000, 1e-3) << "Lz / 3";
  EXPECT_EQ(SkyLuminance(overcast, {0, -0.5, std::sqrt(0.75)}), 0) << "no ground";
  const Vec3 sun = Normalize(Vec3{0, 1, 1});  // 45 degrees up toward +Z
  const Sky clear{SkyKind::kCieClear, 2000, sun};
  EXPECT_NEAR(SkyLuminance(clear, {0, 1, 0}), 2000, 1e-9) << "Lz at the zenith";
  // Brightest around the sun, darker on the far side at the same altitude.
  EXPECT_GT(SkyLuminance(clear, sun), 3 * SkyLuminance(clear, Normalize(Vec3{0, 1, -1})));
  const Sky uniform{SkyKind::kUniform, 500, {0, 1, 0}};
  EXPECT_EQ(SkyLuminance(uniform, Normalize(Vec3{0.3, 0.1, 0.4})), 500);
  EXPECT_EQ(SkyLuminance(Sky{}, {0, 1, 0}), 0);
}

TEST(SkyTest, HorizontalIlluminanceHasItsClosedFormsAndAgreesWithAnotherQuadrature) {
  EXPECT_DOUBLE_EQ(SkyHorizontalIlluminance({SkyKind::kUniform, 1000, {0, 1, 0}}), kPi * 1000);
  const Sky overcast{SkyKind::kCieOvercast, 900, {0, 1, 0}};
  EXPECT_DOUBLE_EQ(SkyHorizontalIlluminance(overcast), 7 * kPi * 900 / 9);
  EXPECT_NEAR(HorizontalByThetaPhi(overcast), 7 * kPi * 900 / 9, 1e-4 * 7 * kPi * 100);
  for (const Vec3& sun : {Normalize(Vec3{0, 1, 1}), Normalize(Vec3{1, 0.2, 0.3}), Vec3{0, 1, 0}}) {
    const Sky clear{SkyKind::kCieClear, 1000, sun};
    const double e = SkyHorizontalIlluminance(clear);
    EXPECT_NEAR(e, HorizontalByThetaPhi(clear), 2e-3 * e) << sun.x << " " << sun.y;
  }
}

TEST(SkyTest, ProblemsAreNamed) {
  EXPECT_EQ(SkyProblem({SkyKind::kCieOvercast, 100, {0, 1, 0}}), "");
  EXPECT_NE(SkyProblem({SkyKind::kUniform, -1, {0, 1, 0}}), "");
  EXPECT_NE(SkyProblem({SkyKind::kUniform, NAN, {0, 1, 0}}), "");
  EXPECT_NE(SkyProblem({SkyKind::kCieClear, 100, {0, 2, 0}}), "");
  EXPECT_NE(SkyProblem({static_cast<SkyKind>(7), 100, {0, 1, 0}}), "");
}

TEST(SkyTest, AUniformSkyOverAnOpenFloorGivesPiL) {
  const PatchScene scene = OpenFloor({SkyKind::kUniform, 1234, {0, 1, 0}});
  double power = 0;
  const std::vector<Rgb> e = PatchDirectLight(scene, 4, 7, 2, true, &power);
  ASSERT_EQ(e.size(), scene.patches.size());
  double area = 0;
  for (size_t i = 0; i < e.size(); ++i) {
    // Every ray leaves the scene: E / pi = L to rounding.
    EXPECT_NEAR(e[i].r * kPi, kPi * 1234, 1e-9 * 1234) << i;
    area += scene.patches[i].area;
  }
  EXPECT_NEAR(power, area * 3 * 1234, 1e-6 * power) << "the sky's power in the energy account";
}

TEST(SkyTest, AnOvercastSkyOverAnOpenFloorGivesSevenNinthsPiLz) {
  const PatchScene scene = OpenFloor({SkyKind::kCieOvercast, 900, {0, 1, 0}});
  const std::vector<Rgb> e = PatchDirectLight(scene, 4, 7, 2);
  for (size_t i = 0; i < e.size(); ++i) {
    EXPECT_NEAR(e[i].g * kPi, 7 * kPi * 900 / 9, 2e-3 * 7 * kPi * 100) << i;
  }
}

TEST(SkyTest, ARoofWithAHoleLetsInTheSkyTheHoleSubtends) {
  // A 2 x 2 roof at y = 1 over the floor's centre, facing down, with a 1 x 1 hole in its middle
  // (four strips around it).
  PatchScene scene = OpenFloor({SkyKind::kUniform, 100, {0, 1, 0}});
  const testing::Surface roof{{0.5, 0.5, 0.5}, {}, 1};
  // Facing down: counter-clockwise seen from below.
  const auto add = [&](double x0, double z0, double x1, double z1) {
    testing::AddQuadGrid({x0, 1, z0}, {x1, 1, z0}, {x1, 1, z1}, {x0, 1, z1}, 1, roof, &scene);
  };
  add(-1, -1, 1, -0.5);
  add(-1, 0.5, 1, 1);
  add(-1, -0.5, -0.5, 0.5);
  add(0.5, -0.5, 1, 0.5);
  // A floor point sees the sky through the hole and past the roof's edges: E / pi = L (1 - F),
  // F the roof's form factor from the point in closed form (the strips' sum).
  const Vec3 x{0.1, 0, -0.05}, n{0, 1, 0};
  double roof_f = 0;
  for (size_t i = 16; i < scene.patches.size(); ++i) {
    roof_f += PointToPatchFormFactor(x, n, scene.patches[i]);
  }
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster, 256);
  ASSERT_EQ(direct.sky_rays(), kMaxSkyRaysPerPoint);
  const double e = direct.SkyIrradiance(x, n, 3).r;
  EXPECT_NEAR(e, 100 * (1 - roof_f), 0.01 * 100 * (1 - roof_f)) << "F(roof) " << roof_f;
}

TEST(SkyTest, TheStartsPiecesGiveTheWholesBits) {
  PatchScene scene = OpenFloor({SkyKind::kCieClear, 800, Normalize(Vec3{1, 2, 0.5})}, 6);
  testing::AddQuadGrid({-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5}, 2,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 1}, &scene);
  const StartWork work{4, 5, true, 0};
  const RayCaster caster(scene);
  const DirectLight direct = StartDirectLight(scene, caster, work);
  const size_t n = scene.patches.size();
  const PatchStartValues whole = TraceStartPatches(scene, direct, caster, work, 0, n, 1);
  ASSERT_EQ(whole.punctual.size(), n) << "the sky's share kept apart";
  PatchStartValues pieces;
  const size_t cuts[] = {0, 5, 21, n};
  for (size_t k = 0; k + 1 < std::size(cuts); ++k) {
    AppendStartValues(TraceStartPatches(scene, direct, caster, work, cuts[k], cuts[k + 1], 2),
                      &pieces);
  }
  EXPECT_TRUE(testing::BitIdentical(pieces.direct, whole.direct));
  EXPECT_TRUE(testing::BitIdentical(pieces.punctual, whole.punctual));
  EXPECT_EQ(pieces.rays, whole.rays);
  EXPECT_EQ(whole.rays, uint64_t(n) * 16 * kSkyRaysPerPoint);
}

TEST(SkyTest, ASkyAloneStartsTheSolveFromItsDirectLight) {
  const PatchScene scene = OpenFloor({SkyKind::kCieOvercast, 900, {0, 1, 0}});
  EXPECT_GT(DirectLightSections(scene, testing::Gathering(2048)), 0u);
  SolverSettings off = testing::Gathering(0);
  EXPECT_GT(DirectLightSections(scene, off), 0u) << "as the lamps: nothing else shoots it";
  const std::string why = DirectStartRule(scene, testing::Gathering(2048)).why;
  EXPECT_EQ(why.rfind("from the direct light of the sky alone, at 4 x 4 points per patch", 0), 0u)
      << why;
}

}  // namespace
}  // namespace radfarm
