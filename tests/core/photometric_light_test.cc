// Photometric lamps (core/punctual_light.h with a core/candela_table.h): the irradiance an IES
// table predicts, I(theta, phi) cos / d^2, in the solver's direct light; the lamp's orientation;
// its power in the solve's account; the same bits on any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/back_face_survey.h"
#include "core/direct_light.h"
#include "core/progressive_solver.h"
#include "core/punctual_light.h"
#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

// 1000 cd cos(theta) every 5 degrees over the lower hemisphere, as the IES fixture's downlight.
CandelaTable CosineDownlight() {
  CandelaTable table;
  table.horizontal = {0};
  for (int a = 0; a <= 90; a += 5) {
    table.vertical.push_back(a);
    table.candela.push_back(a == 90 ? 0 : 1000 * std::cos(a * std::numbers::pi / 180));
  }
  return table;
}

// Every plane measured: straight down 100 cd at phi 0, 200 at 90, 300 at 180, 400 at 270.
CandelaTable FourPlanes() {
  return CandelaTable{{0, 90}, {0, 90, 180, 270, 360}, {100, 0, 200, 0, 300, 0, 400, 0, 100, 0}};
}

// A grey 4 x 4 floor [-2, 2]^2 at z = 0, facing up, lit by `light`.
PatchScene IesFloor(const PunctualLight& light) {
  PatchScene scene;
  testing::AddQuadGrid({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, 4,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 0}, &scene);
  scene.lights = {light};
  return scene;
}

TEST(PhotometricLightTest, GivesTheIlluminanceTheTablePredicts) {
  const Vec3 at{0.3, -0.2, 2};
  const CandelaTable table = CosineDownlight();
  const PunctualLight lamp = MakePhotometricLight(at, {0, 0, -1}, {1, 0, 0}, {1, 1, 1}, table);
  ASSERT_EQ(PunctualLightProblem(lamp), "");
  const std::vector<ReceiverPoint> points = {
      {{0.3, -0.2, 0}, {0, 0, 1}}, {{1.3, 0.8, 0}, {0, 0, 1}}, {{-1.7, 1.9, 0}, {0, 0, 1}}};
  const std::vector<Rgb> e = PointsDirectLight(IesFloor(lamp), points, 3, 2);
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = at - points[i].position;
    const double r2 = Dot(d, d);
    const double cos_theta = d.z / std::sqrt(r2);
    const double theta = std::acos(cos_theta) * 180 / std::numbers::pi;
    const double lux = CandelaAt(table, theta, 0) * cos_theta / r2;
    EXPECT_NEAR(e[i].g * std::numbers::pi, lux, 1e-9 * lux) << i;
  }
  // Straight below: 1000 cd at 2 m, 250 lx; the cosine table within its 5-degree chords.
  EXPECT_NEAR(e[0].r * std::numbers::pi, 250, 1e-9);
}

TEST(PhotometricLightTest, TheReferenceSetsWhereTheHorizontalAnglesTurn) {
  // Aimed down with phi 0 toward +x: phi 90 lies toward +y.
  PunctualLight lamp =
      MakePhotometricLight({0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {1, 1, 1}, FourPlanes());
  const Vec3 down{0, 0, -1};
  EXPECT_DOUBLE_EQ(PhotometricCandela(lamp, down), 100);
  // Just off the nadir, so the plane shows: the vertical angle is tiny, the candela its plane's.
  const auto toward = [&](const Vec3& side) {
    return PhotometricCandela(lamp, Normalize(down + side * 1e-9));
  };
  EXPECT_NEAR(toward({1, 0, 0}), 100, 1e-6);
  EXPECT_NEAR(toward({0, 1, 0}), 200, 1e-6);
  EXPECT_NEAR(toward({-1, 0, 0}), 300, 1e-6);
  EXPECT_NEAR(toward({0, -1, 0}), 400, 1e-6);
  // Turned a quarter: phi 0 toward +y, so +x is at phi 270.
  lamp.reference = {0, 1, 0};
  EXPECT_NEAR(toward({1, 0, 0}), 400, 1e-6);
  EXPECT_NEAR(toward({0, 1, 0}), 100, 1e-6);
  // Aimed up, nothing below the horizon of a table that stops at 90 degrees.
  lamp.direction = {0, 0, 1};
  lamp.reference = {1, 0, 0};
  EXPECT_EQ(UnshadowedIrradiance(lamp, {0, 0, 0}, {0, 0, 1}), Rgb{});
}

TEST(PhotometricLightTest, ItsPowerIsTheTablesLumens) {
  PatchScene scene =
      testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 4, testing::Surface{{0.6, 0.6, 0.6}, {}, 0});
  const PunctualLight lamp =
      MakePhotometricLight({0.5, 0.5, 0.8}, {0, 0, -1}, {1, 0, 0}, {1, 1, 1}, CosineDownlight());
  // 1000 cd cos(theta) below: pi 1000 lm, less what the 5-degree chords leave out.
  EXPECT_NEAR(lamp.table_lumens, std::numbers::pi * 1000, 3);
  EXPECT_DOUBLE_EQ(PunctualPower(lamp), lamp.table_lumens / std::numbers::pi * 3);
  scene.lights = {lamp};
  SolverSettings settings = testing::Gathering(0, 2000);
  ProgressiveSolver solver(scene, settings);
  // A closed box takes all of it, in lux / pi per channel; patch averages of 8 x 8 points come
  // within a percent.
  EXPECT_NEAR(solver.energy().emitted, PunctualPower(lamp), 0.01 * PunctualPower(lamp));
  settings.threads = 1;
  ProgressiveSolver single(scene, settings);
  EXPECT_TRUE(testing::BitIdentical(solver.direct_light(), single.direct_light()));
  // The back-face survey shoots from it too: inside the box it meets fronts only.
  scene.material_names = {"wall"};
  const RayCaster caster(scene);
  const BackFaceCounts counts = SurveyBackFaces(scene, caster, 1000);
  EXPECT_EQ(counts.front[0], 1000u);
}

TEST(PhotometricLightTest, NamesWhatIsWrong) {
  PunctualLight lamp =
      MakePhotometricLight({0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {1, 1, 1}, FourPlanes());
  lamp.reference = {0, 0, 1};
  EXPECT_EQ(PunctualLightProblem(lamp),
            "the reference direction is not a unit vector perpendicular to the direction");
  lamp.reference = {1, 0, 0};
  lamp.table = nullptr;
  EXPECT_EQ(PunctualLightProblem(lamp), "a photometric light has no candela table");
  lamp.table = std::make_shared<const CandelaTable>(CandelaTable{{0}, {0}, {-1}});
  EXPECT_EQ(PunctualLightProblem(lamp), "a candela value is negative or not finite");
}

}  // namespace
}  // namespace radfarm
