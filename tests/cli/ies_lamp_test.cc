// IES lamps end to end, as `radfarm render` loads and solves a job: manufacturers' LM-63 files (the
// 2002 and 1995 formats) hung by the job file over an open floor that emits nothing. At the work
// plane's points the solver's direct light and the illuminance report give the lux the files
// predict, the sum of I(theta, phi) cos / d^2 over the lamps (nothing above the plane reflects
// light back down to it), on any number of threads; a file is read only where the scene's own
// files may be, and its errors name it and its line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "base/text_file.h"
#include "cli/job_inputs.h"
#include "core/direct_light.h"
#include "core/ray_caster.h"
#include "input/ies_file.h"
#include "output/illuminance_light.h"
#include "output/illuminance_planes.h"
#include "solve/local_solve.h"

namespace radfarm {
namespace {

constexpr double kPi = std::numbers::pi;
const std::string kIesDir = RADFARM_SOURCE_DIR "/tests/input/data/ies/";

// A lamp as the job below hangs it: aimed straight down (-Y), turned `rotate` degrees.
struct HungLamp {
  std::string file;
  Vec3 position;
  double rotate;
  double multiplier;
};

const HungLamp kLamps[] = {
    {"downlight_lm63_2002.ies", {0.4, 2.5, -0.3}, 0, 1},
    {"asymmetric_lm63_2002.ies", {-1.5, 2.2, 1.2}, 90, 1},
    {"wallwasher_lm63_1995.ies", {1.8, 2.0, 1.5}, 30, 2},
};

// A 10 x 10 m grey floor at y = 0 facing up, with nothing emitting, and a job hanging kLamps
// over it with a work plane 0.8 m up; the first lamp's file is `first_file`. Returns the job
// file's path.
std::string WriteJob(const std::string& name, const std::string& first_file) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "floor.obj") << "mtllib floor.mtl\nv -5 0 -5\nv -5 0 5\nv 5 0 5\n"
                                      "v 5 0 -5\nusemtl grey\nf 1 2 3 4\n";
  std::ofstream(dir / "floor.mtl") << "newmtl grey\nKd 0.5 0.5 0.5\n";
  std::ofstream job(dir / "job.toml");
  job << "scene = \"floor.obj\"\n[mesh]\npatch_size = 1\n[solver]\nrays = 200000\n";
  for (const HungLamp& lamp : kLamps) {
    std::filesystem::copy_file(kIesDir + lamp.file, dir / lamp.file,
                               std::filesystem::copy_options::overwrite_existing);
    job << "[[lamps]]\nfile = \"" << (&lamp == &kLamps[0] ? first_file : lamp.file)
        << "\"\nposition = [" << lamp.position.x << ", " << lamp.position.y << ", "
        << lamp.position.z << "]\nrotate = " << lamp.rotate << "\nmultiplier = " << lamp.multiplier
        << "\n";
  }
  job << "[[illuminance]]\nname = \"desks\"\nheight = 0.8\nspacing = 1.5\n";
  return (dir / "job.toml").string();
}

// The lux at x on a plane facing up, from the files' tables: horizontal angle 0 of a lamp aimed
// down lies toward +X and 90 toward -Z; turned by r, 0 toward (cos r, 0, -sin r).
double PredictedLux(const Vec3& x) {
  double lux = 0;
  for (const HungLamp& lamp : kLamps) {
    Result<std::string> text = ReadTextFile(kIesDir + lamp.file);
    EXPECT_TRUE(text.ok()) << text.error();
    Result<IesPhotometry> ies = ParseIes(*text, lamp.file);
    EXPECT_TRUE(ies.ok()) << ies.error();
    const Vec3 w = x - lamp.position;  // from the lamp
    const double d = Length(w);
    const double r = lamp.rotate * kPi / 180;
    const Vec3 zero{std::cos(r), 0, -std::sin(r)}, ninety{-std::sin(r), 0, -std::cos(r)};
    const double cos_theta = -w.y / d;
    const double theta = std::acos(cos_theta) * 180 / kPi;
    const double phi = std::atan2(Dot(w, ninety), Dot(w, zero)) * 180 / kPi;
    lux += lamp.multiplier * CandelaAt(ies->table, theta, phi) * cos_theta / (d * d);
  }
  return lux;
}

TEST(IesLampTest, TheWorkPlaneGetsTheLuxTheFilesPredict) {
  std::vector<std::string> warnings;
  Result<LoadedJob> job = LoadJobForSolve(WriteJob("ies_floor", kLamps[0].file), {}, &warnings);
  ASSERT_TRUE(job.ok()) << job.error();
  ASSERT_EQ(job->scene.lights.size(), 3u);
  for (const PunctualLight& lamp : job->scene.lights) {
    EXPECT_EQ(lamp.kind, PunctualKind::kPhotometric);
    EXPECT_EQ(lamp.direction, (Vec3{0, -1, 0}));
  }

  const PatchScene& scene = job->mesh.patch_scene();
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster, kPointShadowRays);
  std::vector<uint32_t> patch_object(scene.patches.size());
  for (uint32_t p = 0; p < patch_object.size(); ++p) patch_object[p] = job->mesh.patch_object(p);
  std::vector<double> lux[2];
  for (uint32_t threads : {1u, 2u}) {
    SolverSettings settings = job->job.solver;
    settings.threads = threads;
    const SolveResult solved = Solve(scene, settings);
    Result<std::vector<PlaneIlluminance>> planes =
        MeasurePlanes({scene, caster, solved.radiosity, solved.direct_light, settings},
                      job->mesh.objects(), patch_object, job->job.illuminance);
    ASSERT_TRUE(planes.ok()) << planes.error();
    const PlaneIlluminance& plane = (*planes)[0];
    ASSERT_GE(plane.lux.size(), 36u);
    double brightest = 0;
    for (size_t i = 0; i < plane.lux.size(); ++i) {
      const ReceiverPoint& point = plane.grid.points[i];
      const double want = PredictedLux(point.position);
      brightest = std::max(brightest, want);
      EXPECT_NEAR(plane.lux[i], want, 1e-6 * want + 1e-9) << "point " << i;
      const double solver = LuxOf(direct.PunctualIrradiance(point.position, point.normal));
      EXPECT_NEAR(solver, want, 1e-9 * want + 1e-12) << "point " << i;
    }
    EXPECT_GT(brightest, 50) << "the lamps light the plane";
    lux[threads - 1] = plane.lux;
  }
  EXPECT_EQ(lux[0], lux[1]) << "the same bits on one thread and two";
}

TEST(IesLampTest, TheFileIsReadOnlyWhereTheScenesFilesMayBe) {
  std::vector<std::string> warnings;
  const std::string path = WriteJob("ies_outside", "../outside.ies");
  Result<LoadedJob> job = LoadJobForSolve(path, {}, &warnings);
  ASSERT_FALSE(job.ok());
  EXPECT_EQ(job.error().rfind(path + ":7: 'lamps[0].file' '../outside.ies' leads outside", 0), 0u)
      << job.error();
}

TEST(IesLampTest, AnUnusableFileIsNamedWithItsLine) {
  std::vector<std::string> warnings;
  const std::string path = WriteJob("ies_bad", "bad.ies");
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::ofstream(dir / "bad.ies") << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 1 1 2 2 0 0 0\n";
  Result<LoadedJob> job = LoadJobForSolve(path, {}, &warnings);
  ASSERT_FALSE(job.ok());
  EXPECT_EQ(job.error(), (dir / "bad.ies").string() +
                             ":3: photometric type 2 (type B) is not supported: only type C (1)");
}

}  // namespace
}  // namespace radfarm
