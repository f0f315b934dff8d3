// The path-traced reference against closed forms: a white furnace, two parallel squares, a point
// lamp and an IES lamp over a floor, skies over an open floor. Each estimate must land within 3
// standard errors of the exact value, and its standard error must be small (so a bias above
// about 1.5% fails).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "input/scene_loader.h"
#include "reference/path_tracer.h"
#include "reference/reference_scene.h"
#include "tests/reference/reference_test_scenes.h"

namespace radfarm::reference {
namespace {

using testing::AddMaterial;
using testing::AddSquareAt;
using testing::ClosedBox;

constexpr double kPi = std::numbers::pi;

std::unique_ptr<ReferenceScene> BuildOrDie(const InputScene& input) {
  auto scene = ReferenceScene::Build(input);
  EXPECT_TRUE(scene) << (scene ? "" : scene.error());
  return std::move(*scene);
}

SurfacePoint At(const ReferenceScene& scene, Vec3 p, Vec3 n) {
  auto point = LocatePoint(scene, p, n);
  EXPECT_TRUE(point) << (point ? "" : point.error());
  return *point;
}

TraceSettings Tight() {
  TraceSettings s;
  s.relative_error = 0.004;
  s.min_samples = 4096;
  s.max_samples = 1 << 20;
  return s;
}

// Within 3 standard errors per channel, and the standard error itself small.
void ExpectNear(const PointEstimate& e, const Rgb& exact, double max_relative_error) {
  const double channels[3][3] = {{e.radiance.r, e.standard_error.r, exact.r},
                                 {e.radiance.g, e.standard_error.g, exact.g},
                                 {e.radiance.b, e.standard_error.b, exact.b}};
  for (const auto& [value, se, want] : channels) {
    EXPECT_NEAR(value, want, 3 * se + 1e-12) << "standard error " << se;
    EXPECT_LE(se, max_relative_error * std::max(want, 1e-12)) << "exact " << want;
  }
}

// Form factor from a point to a parallel rectangle a x b (in units of the distance) whose corner
// lies straight above it.
double CornerFormFactor(double a, double b) {
  const double ra = std::sqrt(1 + a * a), rb = std::sqrt(1 + b * b);
  return (a / ra * std::atan(b / ra) + b / rb * std::atan(a / rb)) / (2 * kPi);
}

TEST(ReferenceClosedFormsTest, FurnaceGivesEmissionOverOneMinusReflectance) {
  // Every channel different, so the channels cannot be mixed up: B = Le / (1 - rho).
  const Rgb rho{0.5, 0.7, 0.8}, le{1, 2, 0.5};
  const auto scene = BuildOrDie(ClosedBox(2, rho, le));
  const PathTracer tracer(*scene);
  const Rgb exact{1 / 0.5, 2 / 0.3, 0.5 / 0.2};
  const SurfacePoint points[] = {At(*scene, {1, 1, 0}, {0, 0, 1}),
                                 At(*scene, {0, 1.99, 1}, {1, 0, 0}),
                                 At(*scene, {2, 0.3, 0.001}, {-1, 0, 0})};
  for (uint32_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    // The stopping rule holds the channel sum to 0.4%; blue, the dimmest, gets about 0.8%.
    ExpectNear(tracer.Estimate(points[i], i, Tight()), exact, 0.01);
  }
}

TEST(ReferenceClosedFormsTest, FurnaceFromTheSceneFile) {
  // scenes/furnace.obj: rho 0.9, Ke 1, B = 10; long paths, so Russian roulette must be unbiased.
  auto input = LoadScene(std::string(RADFARM_SOURCE_DIR) + "/scenes/furnace.obj");
  ASSERT_TRUE(input) << input.error();
  const auto scene = BuildOrDie(*input);
  TraceSettings s = Tight();
  s.relative_error = 0.005;
  const PointEstimate e = PathTracer(*scene).Estimate(At(*scene, {0.3, 0, 0.6}, {0, 1, 0}), 0, s);
  ExpectNear(e, {10, 10, 10}, 0.006);
}

// A receiver of reflectance rho at z = 0 under a black emitter of radiance 1 at z = d: the
// receiver's radiance at a point is rho times the point's form factor to the emitter.
class ParallelSquaresTest : public ::testing::TestWithParam<double> {};

TEST_P(ParallelSquaresTest, ReceiverMatchesTheFormFactor) {
  const double d = GetParam();
  InputScene input;
  input.path = "squares";
  const uint32_t receiver = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
  const uint32_t emitter = AddMaterial(&input, {}, {1, 1, 1});
  AddSquareAt(&input, 0, true, receiver);
  AddSquareAt(&input, d, false, emitter);
  const auto scene = BuildOrDie(input);
  const PathTracer tracer(*scene);
  const double centre = 0.5 * 4 * CornerFormFactor(0.5 / d, 0.5 / d);
  const double corner = 0.5 * CornerFormFactor(1 / d, 1 / d);
  // A point a quarter of the way in: four rectangles of 0.25 and 0.75 sides.
  const double a = 0.25 / d, b = 0.75 / d;
  const double quarter =
      0.5 * (CornerFormFactor(a, a) + 2 * CornerFormFactor(a, b) + CornerFormFactor(b, b));
  ExpectNear(tracer.Estimate(At(*scene, {0.5, 0.5, 0}, {0, 0, 1}), 0, Tight()),
             {centre, centre, centre}, 0.005);
  ExpectNear(tracer.Estimate(At(*scene, {0.25, 0.25, 0}, {0, 0, 1}), 1, Tight()),
             {quarter, quarter, quarter}, 0.005);
  ExpectNear(tracer.Estimate(At(*scene, {1e-4, 1e-4, 0}, {0, 0, 1}), 2, Tight()),
             {corner, corner, corner}, 0.006);
}

// From far (next-event estimation does the work) to very near (the cosine-weighted directions do).
INSTANTIATE_TEST_SUITE_P(Distances, ParallelSquaresTest, ::testing::Values(2.0, 1.0, 0.2, 0.02));

TEST(ReferenceClosedFormsTest, BackOfAOneSidedSurfaceAbsorbsAndTwoSidedEmitsBothWays) {
  // The emitter faces away from the receiver: one-sided, nothing arrives; two-sided, its back
  // emits as its front.
  for (bool two_sided : {false, true}) {
    InputScene input;
    input.path = "squares";
    const uint32_t receiver = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
    const uint32_t emitter = AddMaterial(&input, {}, {1, 1, 1}, two_sided);
    AddSquareAt(&input, 0, true, receiver);
    AddSquareAt(&input, 1, true, emitter);
    const auto scene = BuildOrDie(input);
    const PointEstimate e =
        PathTracer(*scene).Estimate(At(*scene, {0.5, 0.5, 0}, {0, 0, 1}), 0, Tight());
    const double exact = two_sided ? 0.5 * 4 * CornerFormFactor(0.5, 0.5) : 0;
    SCOPED_TRACE(two_sided);
    EXPECT_NEAR(e.radiance.g, exact, 3 * e.standard_error.g + 1e-12);
    if (!two_sided) {
      EXPECT_EQ(e.radiance.g, 0);
    }
  }
}

TEST(ReferenceClosedFormsTest, PointLampOverAFloor) {
  // I cd at height h, the point at horizontal distance x: rho I cos / (pi r^2), cos = h / r.
  InputScene input;
  input.path = "lamp";
  const uint32_t floor = AddMaterial(&input, {0.6, 0.6, 0.6}, {});
  AddSquareAt(&input, 0, true, floor);
  PunctualLight lamp;
  lamp.position = {0.5, 0.5, 2};
  lamp.intensity = {3, 3, 3};
  input.lights.push_back(lamp);
  const auto scene = BuildOrDie(input);
  const SurfacePoint p = At(*scene, {0.9, 0.5, 0}, {0, 0, 1});
  const double r2 = 0.4 * 0.4 + 4, cos = 2 / std::sqrt(r2);
  const double exact = 0.6 * 3 * cos / (kPi * r2);
  const PointEstimate e = PathTracer(*scene).Estimate(p, 0, Tight());
  EXPECT_NEAR(e.radiance.r, exact, 1e-6 * exact);  // one bounce, no randomness
}

// An IES lamp aimed down (-z) with horizontal angle 0 toward +x, so 90 lies toward +y: each point
// 45 degrees off the nadir in one of the four planes gets that plane's candela, I cos / (pi r^2)
// with cos = 1 / sqrt 2. On the floor 0.3 m below (r^2 = 0.18) times rho; at free points facing
// up 0.2 m below (r^2 = 0.08) as it is.
TEST(ReferenceClosedFormsTest, PhotometricLampOverAFloorTurnsAsItsTable) {
  const CandelaTable table{{0, 45, 90},
                           {0, 90, 180, 270, 360},
                           {100, 80, 0, 200, 160, 0, 300, 240, 0, 400, 320, 0, 100, 80, 0}};
  const Vec3 lamp{0.5, 0.5, 0.3};
  InputScene input;
  input.path = "ies";
  AddSquareAt(&input, 0, true, AddMaterial(&input, {0.6, 0.6, 0.6}, {}));
  input.lights.push_back(MakePhotometricLight(lamp, {0, 0, -1}, {1, 0, 0}, {1, 1, 1}, table));
  const auto scene = BuildOrDie(input);
  const PathTracer tracer(*scene);
  const struct {
    Vec3 plane;  // the horizontal direction of the plane
    double candela;
  } cases[] = {{{1, 0, 0}, 80}, {{0, 1, 0}, 160}, {{-1, 0, 0}, 240}, {{0, -1, 0}, 320}};
  for (const auto& c : cases) {
    const double on_floor = c.candela / std::sqrt(2.0) / (kPi * 0.18);
    const Vec3 floor = lamp + c.plane * 0.3 - Vec3{0, 0, 0.3};
    const PointEstimate on = tracer.Estimate(At(*scene, floor, {0, 0, 1}), 0, Tight());
    EXPECT_NEAR(on.radiance.r, 0.6 * on_floor, 1e-6 * on_floor) << c.candela;  // no randomness
    const double free = c.candela / std::sqrt(2.0) / (kPi * 0.08);
    const PointEstimate above =
        tracer.EstimateIrradiance(lamp + c.plane * 0.2 - Vec3{0, 0, 0.2}, {0, 0, 1}, 0, Tight());
    EXPECT_NEAR(above.radiance.r, free, 1e-9 * free) << c.candela;
  }
}

// A calculation point in open space (an illuminance report's): E / pi, the radiance a white
// surface there would reflect. In a furnace every direction sees B = Le / (1 - rho); under a lamp
// over a floor, facing up, only the lamp: I cos / (pi r^2).
TEST(ReferenceClosedFormsTest, IrradianceAtAFreePoint) {
  const auto box = BuildOrDie(ClosedBox(2, {0.5, 0.7, 0.8}, {1, 2, 0.5}));
  ExpectNear(PathTracer(*box).EstimateIrradiance({1, 0.7, 1}, {0, 0, 1}, 0, Tight()),
             {1 / 0.5, 2 / 0.3, 0.5 / 0.2}, 0.01);

  InputScene input;
  input.path = "lamp";
  AddSquareAt(&input, 0, true, AddMaterial(&input, {0.6, 0.6, 0.6}, {}));
  PunctualLight lamp;
  lamp.position = {0.5, 0.5, 2};
  lamp.intensity = {3, 3, 3};
  input.lights.push_back(lamp);
  const auto scene = BuildOrDie(input);
  const double r2 = 0.4 * 0.4 + 1.2 * 1.2, cos = 1.2 / std::sqrt(r2);
  const PointEstimate e =
      PathTracer(*scene).EstimateIrradiance({0.9, 0.5, 0.8}, {0, 0, 1}, 0, Tight());
  EXPECT_NEAR(e.radiance.r, 3 * cos / (kPi * r2), 1e-9);  // the lamp alone: no randomness

  std::vector<Vec3> positions, normals;
  for (int i = 0; i < 4; ++i) {
    positions.push_back({0.2 + 0.2 * i, 0.5, 0.5});
    normals.push_back({0, 0, 1});
  }
  TraceSettings s;
  s.min_samples = s.max_samples = 256;
  s.threads = 1;
  const std::vector<PointEstimate> one =
      PathTracer(*box).EstimateIrradianceAll(positions, normals, s);
  s.threads = 3;
  const std::vector<PointEstimate> three =
      PathTracer(*box).EstimateIrradianceAll(positions, normals, s);
  for (size_t i = 0; i < positions.size(); ++i) {
    EXPECT_EQ(one[i].radiance, three[i].radiance) << i;
    EXPECT_EQ(one[i].radiance,
              PathTracer(*box).EstimateIrradiance(positions[i], normals[i], i, s).radiance);
  }
}

TEST(ReferenceClosedFormsTest, EstimatesDoNotDependOnThreads) {
  const auto scene = BuildOrDie(ClosedBox(1, {0.5, 0.5, 0.5}, {1, 1, 1}));
  std::vector<SurfacePoint> points;
  for (int i = 0; i < 5; ++i) points.push_back(At(*scene, {0.1 + 0.2 * i, 0.5, 0}, {0, 0, 1}));
  TraceSettings s;
  s.min_samples = s.max_samples = 512;
  s.threads = 1;
  const std::vector<PointEstimate> one = PathTracer(*scene).EstimateAll(points, s);
  s.threads = 3;
  const std::vector<PointEstimate> three = PathTracer(*scene).EstimateAll(points, s);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(one[i].radiance, three[i].radiance);
    EXPECT_EQ(one[i].samples, three[i].samples);
  }
  EXPECT_NE(one[0].radiance, one[1].radiance);  // different points draw different numbers
}

TEST(ReferenceClosedFormsTest, SkiesOverAnOpenFloorGivePiLAndSevenNinthsPiLz) {
  // A grey floor facing +Y (the sky's up); a point above it sees the whole dome.
  InputScene input;
  input.path = "floor";
  const uint32_t grey = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
  testing::AddQuad(&input, {Vec3{-5, 0, -5}, Vec3{-5, 0, 5}, Vec3{5, 0, 5}, Vec3{5, 0, -5}}, grey);
  input.sky = {SkyKind::kUniform, 300, {0, 1, 0}};
  auto scene = BuildOrDie(input);
  PathTracer tracer(*scene);
  // Irradiance over pi: every path escapes at once with L.
  ExpectNear(tracer.EstimateIrradiance({0.2, 0.5, 0.1}, {0, 1, 0}, 0, Tight()), {300, 300, 300},
             0.004);
  // On the floor: rho L, the floor seeing the uniform sky alone.
  ExpectNear(tracer.Estimate(At(*scene, {0.2, 0, 0.1}, {0, 1, 0}), 1, Tight()), {150, 150, 150},
             0.004);
  input.sky = {SkyKind::kCieOvercast, 900, {0, 1, 0}};
  scene = BuildOrDie(input);
  PathTracer overcast(*scene);
  ExpectNear(overcast.EstimateIrradiance({0.2, 0.5, 0.1}, {0, 1, 0}, 2, Tight()), {700, 700, 700},
             0.01);
}

}  // namespace
}  // namespace radfarm::reference
