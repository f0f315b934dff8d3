#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "job/job.h"
#include "tests/input/test_files.h"

namespace radfarm {
namespace {

using testing::DataPath;
using testing::WriteScratchFile;

std::string JobError(const std::string& path) {
  Result<Job> job = LoadJob(path);
  EXPECT_FALSE(job.ok()) << path << " loaded but should not have";
  if (job.ok()) return "";
  EXPECT_EQ(job.error().find('\n'), std::string::npos) << job.error();
  return job.error();
}

void ExpectDefaults(const Job& job) {
  const Job defaults;
  EXPECT_EQ(job.mesh.patch_size, defaults.mesh.patch_size);
  EXPECT_EQ(job.solver.sampler, defaults.solver.sampler);
  EXPECT_EQ(job.solver.seed, defaults.solver.seed);
  EXPECT_EQ(job.solver.tolerance, defaults.solver.tolerance);
  EXPECT_EQ(job.solver.max_rays, defaults.solver.max_rays);
  EXPECT_EQ(job.solver.shot_rays, defaults.solver.shot_rays);
  EXPECT_EQ(job.solver.overrelaxation, 1.0);
  EXPECT_TRUE(job.camera.automatic);
  EXPECT_TRUE(job.camera.auto_exposure);
  EXPECT_EQ(job.camera.width, defaults.camera.width);
  EXPECT_EQ(job.camera.fov_degrees, defaults.camera.fov_degrees);
}

TEST(LoadJobTest, BareObjGetsDefaults) {
  Result<Job> job = LoadJob("scenes/cornell-box.obj");
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->scene_path, "scenes/cornell-box.obj");
  ExpectDefaults(*job);
  EXPECT_TRUE(LoadJob("scenes/BOX.OBJ").ok());
}

TEST(LoadJobTest, OtherExtensionsAreRefused) {
  EXPECT_EQ(JobError("scene.ply"),
            "scene.ply: not a scene: expected a .obj, .gltf, .glb or a .toml job file");
}

TEST(LoadJobTest, MissingJobFile) {
  EXPECT_EQ(JobError(DataPath("jobs/none.toml")),
            DataPath("jobs/none.toml") + ": cannot open: No such file or directory");
}

// A job file is refused from its size before it is read (a sparse 2 GiB file: nothing
// is read or allocated), and a FIFO named like a job file is refused without waiting for a writer.
TEST(LoadJobTest, AJobFileOverTheLimitOrNotARegularFileIsRefusedBeforeReading) {
  const std::string big = WriteScratchFile("big.toml", "");
  std::filesystem::resize_file(big, uint64_t{2} << 30);
  EXPECT_EQ(JobError(big),
            big + ": the file is 2147483648 bytes, over the limit of 16777216 bytes");
  const std::string fifo = std::filesystem::path(big).parent_path() / "pipe.toml";
  std::filesystem::remove(fifo);  // from an earlier run
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(JobError(fifo), fifo + ": cannot open: not a regular file (a FIFO)");
  std::filesystem::remove(big);
  std::filesystem::remove(fifo);
}

TEST(LoadJobTest, MinimalJobKeepsDefaultsAndResolvesTheSceneBesideIt) {
  Result<Job> job = LoadJob(DataPath("jobs/minimal.toml"));
  ASSERT_TRUE(job.ok()) << job.error();
  ExpectDefaults(*job);
  EXPECT_EQ(job->scene_path, DataPath("jobs/../polygons.obj"));
  EXPECT_TRUE(std::filesystem::equivalent(job->scene_path, DataPath("polygons.obj")));
}

TEST(LoadJobTest, SceneRelativeToAJobGivenByRelativePath) {
  const std::filesystem::path saved = std::filesystem::current_path();
  std::filesystem::current_path(DataPath(""));
  Result<Job> job = LoadJob("jobs/minimal.toml");
  std::filesystem::current_path(saved);
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->scene_path, "jobs/../polygons.obj");
}

TEST(LoadJobTest, AbsoluteScenePathIsKept) {
  Result<Job> job = LoadJob(WriteScratchFile("abs.toml", "scene = \"/data/room.obj\"\n"));
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->scene_path, "/data/room.obj");
}

TEST(LoadJobTest, FromIsRelativeToTheJobFileAndNotEmpty) {
  const std::string path = WriteScratchFile("from.toml", "scene = \"x.obj\"\nfrom = \"out\"\n");
  Result<Job> job = LoadJob(path);
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->from, (std::filesystem::path(path).parent_path() / "out").string());
  EXPECT_EQ(LoadJob(WriteScratchFile("abs.toml", "scene = \"x.obj\"\n"))->from, "");
  const std::string empty = WriteScratchFile("from_empty.toml", "scene = \"x.obj\"\nfrom = \"\"\n");
  EXPECT_EQ(JobError(empty).rfind(empty + ":2: 'from' must not be empty", 0), 0u)
      << JobError(empty);
}

TEST(LoadJobTest, ReadsEveryKey) {
  Result<Job> job = LoadJob(DataPath("jobs/full.toml"));
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->mesh.patch_size, 30.0);
  const SolverSettings& s = job->solver;
  EXPECT_EQ(s.sampler, SamplerKind::kGrid);
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.tolerance, 0.01);
  EXPECT_EQ(s.max_rays, 1000000u);
  EXPECT_EQ(s.max_seconds, 2.5);
  EXPECT_EQ(s.shot_rays, 1000u);
  EXPECT_EQ(s.min_shooter_rays, 16u);
  EXPECT_EQ(s.shooters_per_round, 8u);
  EXPECT_EQ(s.overrelaxation, 1.5);
  EXPECT_EQ(s.grid_step_degrees, 2.0);
  EXPECT_EQ(s.threads, 3u);
  const Camera& c = job->camera;
  EXPECT_FALSE(c.automatic);
  EXPECT_EQ(c.eye, Vec3(278, 273, -800));
  EXPECT_EQ(c.target, Vec3(278, 273, 0));
  EXPECT_EQ(c.up, Vec3(1, 0, 0));
  EXPECT_EQ(c.fov_degrees, 39.3077);
  EXPECT_EQ(c.width, 640u);
  EXPECT_EQ(c.height, 480u);
  EXPECT_EQ(c.exposure, -1.5);
  EXPECT_FALSE(c.auto_exposure);
  EXPECT_EQ(c.samples_per_pixel, 9u);
  EXPECT_EQ(job->lightmap_size, 512u);
  EXPECT_EQ(job->lightmap_texel, 0.0);
}

TEST(LoadJobTest, LightmapsAreAutomaticUnlessASizeOrTexelIsGiven) {
  const Job defaults;
  EXPECT_EQ(defaults.lightmap_size, 0u);
  EXPECT_EQ(defaults.lightmap_texel, 0.0);
  const auto load = [](const std::string& name, const std::string& output) {
    return LoadJob(WriteScratchFile(name, "scene = \"x.obj\"\n[output]\n" + output));
  };
  Result<Job> sized = load("lm_size.toml", "lightmap_size = 64\n");
  ASSERT_TRUE(sized.ok()) << sized.error();
  EXPECT_EQ(sized->lightmap_size, 64u);
  EXPECT_EQ(sized->lightmap_texel, 0.0);
  for (const char* ends : {"lightmap_size = 16\n", "lightmap_size = 8192\n"}) {
    EXPECT_TRUE(load("lm_ends.toml", ends).ok()) << ends;
  }
  Result<Job> automatic = load("lm_zero.toml", "lightmap_size = 0\n");
  ASSERT_TRUE(automatic.ok()) << automatic.error();
  EXPECT_EQ(automatic->lightmap_size, 0u);
  // A texel size with an explicit 0 (automatic) size is not a conflict.
  Result<Job> texel = load("lm_texel.toml", "lightmap_size = 0\nlightmap_texel = 0.05\n");
  ASSERT_TRUE(texel.ok()) << texel.error();
  EXPECT_EQ(texel->lightmap_size, 0u);
  EXPECT_EQ(texel->lightmap_texel, 0.05);
}

TEST(LoadJobTest, ExposureAloneKeepsTheAutomaticCamera) {
  Result<Job> job =
      LoadJob(WriteScratchFile("exp.toml", "scene = \"x.obj\"\n[camera]\nexposure = 0\n"));
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_TRUE(job->camera.automatic);
  EXPECT_FALSE(job->camera.auto_exposure);
}

TEST(LoadJobTest, UnknownKeyNamesLineAndDottedKey) {
  const std::string path = DataPath("jobs/unknown_key.toml");
  EXPECT_EQ(JobError(path), path + ":7: unknown key 'solver.sampel'");
}

TEST(LoadJobTest, RefineKeysAreReadAndOffByDefault) {
  const Job defaults;
  EXPECT_FALSE(defaults.refine.enabled);
  const std::string path =
      WriteScratchFile("refine.toml",
                       "scene = \"x.obj\"\n[mesh]\nrefine = true\nrefine_tolerance = 0.2\n"
                       "min_element_size = 3\nmax_elements = 5000\n");
  Result<Job> job = LoadJob(path);
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_TRUE(job->refine.enabled);
  EXPECT_EQ(job->refine.tolerance, 0.2);
  EXPECT_EQ(job->refine.min_element_size, 3.0);
  EXPECT_EQ(job->refine.max_elements, 5000u);
}

TEST(LoadJobTest, RefineKeyErrorsNameLineAndKey) {
  const std::string not_bool =
      WriteScratchFile("refine_bool.toml", "scene = \"x.obj\"\n[mesh]\nrefine = 1\n");
  EXPECT_EQ(JobError(not_bool),
            not_bool + ":3: 'mesh.refine' must be true or false, not an integer");
  const std::string zero =
      WriteScratchFile("refine_tol.toml", "scene = \"x.obj\"\n[mesh]\nrefine_tolerance = 0\n");
  EXPECT_EQ(JobError(zero).rfind(zero + ":3: 'mesh.refine_tolerance' must be", 0), 0u)
      << JobError(zero);
  const std::string budget =
      WriteScratchFile("refine_max.toml", "scene = \"x.obj\"\n[mesh]\nmax_elements = 0\n");
  EXPECT_EQ(JobError(budget).rfind(budget + ":3: 'mesh.max_elements' must be", 0), 0u)
      << JobError(budget);
}

TEST(LoadJobTest, IlluminancePlanesAreReadInOrder) {
  const std::string path = WriteScratchFile(
      "planes.toml",
      "scene = \"x.obj\"\n[[illuminance]]\nname = \"desks\"\nheight = 0.8\nspacing = 0.25\n"
      "surfaces = [\"Desk*\", \"table\"]\n[[illuminance]]\nname = \"floor\"\nheight = 0\n"
      "spacing = 1\n");
  Result<Job> job = LoadJob(path);
  ASSERT_TRUE(job.ok()) << job.error();
  ASSERT_EQ(job->illuminance.size(), 2u);
  EXPECT_EQ(job->illuminance[0], (IlluminancePlane{"desks", 0.8, 0.25, {"Desk*", "table"}}));
  EXPECT_EQ(job->illuminance[1], (IlluminancePlane{"floor", 0, 1, {}}));
}

TEST(LoadJobTest, LampsAreReadInOrderWithTheirDefaults) {
  const std::string path = WriteScratchFile(
      "lamps.toml",
      "scene = \"x.obj\"\n[[lamps]]\nfile = \"dl.ies\"\nposition = [1, 2.5, 3]\n[[lamps]]\n"
      "file = \"ww.ies\"\nposition = [0, 2, 0]\naim = [0, 0, -2]\nrotate = 90\n"
      "multiplier = 0.5\n");
  Result<Job> job = LoadJob(path);
  ASSERT_TRUE(job.ok()) << job.error();
  ASSERT_EQ(job->lamps.size(), 2u);
  EXPECT_EQ(job->lamps[0].file, "dl.ies");
  EXPECT_EQ(job->lamps[0].location, path + ":3: 'lamps[0].file'");
  EXPECT_EQ(job->lamps[0].position, (Vec3{1, 2.5, 3}));
  EXPECT_EQ(job->lamps[0].aim, (Vec3{0, -1, 0}));
  EXPECT_EQ(job->lamps[0].rotate, 0);
  EXPECT_EQ(job->lamps[0].multiplier, 1);
  EXPECT_EQ(job->lamps[1].aim, (Vec3{0, 0, -1})) << "made unit";
  EXPECT_EQ(job->lamps[1].rotate, 90);
  EXPECT_EQ(job->lamps[1].multiplier, 0.5);
}

TEST(LoadJobTest, ALampsHorizontalAnglesTurnAsLm63Says) {
  JobLamp lamp;  // aimed down in +Y up: 0 toward +X, 90 toward -Z (counter-clockwise from above)
  const auto near = [](const Vec3& a, const Vec3& b) { return Length(a - b) < 1e-12; };
  EXPECT_TRUE(near(LampReference(lamp), {1, 0, 0}));
  EXPECT_TRUE(near(Cross(LampReference(lamp), lamp.aim), {0, 0, -1}));
  lamp.rotate = 90;
  EXPECT_TRUE(near(LampReference(lamp), {0, 0, -1}));
  lamp.aim = {1, 0, 0};  // along X: 0 toward -Z
  lamp.rotate = 0;
  EXPECT_TRUE(near(LampReference(lamp), {0, 0, -1}));
}

TEST(LoadJobTest, SyntaxErrorGivesTomlsDescriptionAndLine) {
  const std::string path = DataPath("jobs/syntax_error.toml");
  const std::string error = JobError(path);
  EXPECT_EQ(error.rfind(path + ":4: ", 0), 0u) << error;
}

TEST(LoadJobTest, DuplicateKeyIsASyntaxError) {
  const std::string path = WriteScratchFile("dup.toml", "scene = \"x.obj\"\nscene = \"y.obj\"\n");
  const std::string error = JobError(path);
  EXPECT_EQ(error.rfind(path + ":2: ", 0), 0u) << error;
}

TEST(LoadJobTest, MissingScene) {
  const std::string path = WriteScratchFile("noscene.toml", "[mesh]\npatch_size = 1\n");
  EXPECT_EQ(JobError(path), path + ": missing key 'scene'");
}

struct BadJob {
  std::string name;     // names the case in the test list
  std::string body;     // after `scene = "x.obj"` on line 1
  std::string message;  // expected error after "path:"
};

void PrintTo(const BadJob& job, std::ostream* out) { *out << job.name; }

class BadJobTest : public ::testing::TestWithParam<BadJob> {};

TEST_P(BadJobTest, IsRefusedWithFileLineAndKey) {
  const std::string path = WriteScratchFile("job.toml", "scene = \"x.obj\"\n" + GetParam().body);
  EXPECT_EQ(JobError(path), path + ":" + GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(
    Values, BadJobTest,
    ::testing::Values(
        BadJob{"UnknownRootKey", "color = 3\n", "2: unknown key 'color'"},
        BadJob{"IlluminanceNotTables", "illuminance = 3\n",
               "2: 'illuminance' must be an array of tables ([[illuminance]])"},
        BadJob{"IlluminanceWithoutSpacing", "[[illuminance]]\nname = \"a\"\nheight = 1\n",
               "2: 'illuminance[0].spacing' is missing (name, height and spacing are required)"},
        BadJob{"IlluminanceZeroSpacing", "[[illuminance]]\nname = \"a\"\nheight = 1\nspacing = 0\n",
               "5: 'illuminance[0].spacing' must be > 0, got 0"},
        BadJob{"IlluminanceNegativeHeight",
               "[[illuminance]]\nname = \"a\"\nheight = -1\nspacing = 1\n",
               "4: 'illuminance[0].height' must be >= 0, got -1"},
        BadJob{"IlluminanceNameWithSlash",
               "[[illuminance]]\nname = \"a/b\"\nheight = 1\nspacing = 1\n",
               "3: 'illuminance[0].name' must be 1 to 64 letters, digits, '-', '_' or '.', not "
               "starting with '.'"},
        BadJob{"IlluminanceNameRepeated",
               "[[illuminance]]\nname = \"a\"\nheight = 1\nspacing = 1\n"
               "[[illuminance]]\nname = \"a\"\nheight = 2\nspacing = 1\n",
               "7: 'illuminance[1].name' repeats an earlier plane's name"},
        BadJob{"IlluminanceSurfacesNotStrings",
               "[[illuminance]]\nname = \"a\"\nheight = 1\nspacing = 1\nsurfaces = [1]\n",
               "6: 'illuminance[0].surfaces' must be an array of strings, e.g. [\"Desk*\"]"},
        BadJob{"IlluminanceUnknownKey",
               "[[illuminance]]\nname = \"a\"\nheight = 1\nspacing = 1\nspace = 2\n",
               "6: unknown key 'illuminance[0].space'"},
        BadJob{"LampWithoutPosition", "[[lamps]]\nfile = \"a.ies\"\n",
               "2: 'lamps[0].position' is missing (file and position are required)"},
        BadJob{"LampEmptyFile", "[[lamps]]\nfile = \"\"\nposition = [0, 1, 0]\n",
               "3: 'lamps[0].file' must not be empty"},
        BadJob{"LampZeroAim",
               "[[lamps]]\nfile = \"a.ies\"\nposition = [0, 1, 0]\naim = [0, 0, 0]\n",
               "5: 'lamps[0].aim' must be finite and nonzero"},
        BadJob{"LampZeroMultiplier",
               "[[lamps]]\nfile = \"a.ies\"\nposition = [0, 1, 0]\nmultiplier = 0\n",
               "5: 'lamps[0].multiplier' must be > 0, got 0"},
        BadJob{"LampUnknownKey", "[[lamps]]\nfile = \"a.ies\"\nposition = [0, 1, 0]\ntilt = 3\n",
               "5: unknown key 'lamps[0].tilt'"},
        BadJob{"UnknownTable", "[render]\nwidth = 3\n", "2: unknown key 'render'"},
        BadJob{"UnknownCameraKey", "[camera]\nwidht = 3\n", "3: unknown key 'camera.widht'"},
        BadJob{"SectionNotATable", "mesh = 3\n", "2: 'mesh' must be a table, not an integer"},
        BadJob{"PatchSizeZero", "[mesh]\npatch_size = 0\n",
               "3: 'mesh.patch_size' must be > 0, got 0"},
        BadJob{"PatchSizeString", "[mesh]\npatch_size = \"big\"\n",
               "3: 'mesh.patch_size' must be a number, not a string"},
        BadJob{"UnknownSampler", "[solver]\nsampler = \"halton\"\n",
               "3: 'solver.sampler' must be \"grid\", \"random\" or \"sobol\", got \"halton\""},
        BadJob{"SamplerNotString", "[solver]\nsampler = 1\n",
               "3: 'solver.sampler' must be a string, not an integer"},
        BadJob{"NegativeSeed", "[solver]\nseed = -1\n", "3: 'solver.seed' must be >= 0, got -1"},
        BadJob{"RealSeed", "[solver]\nseed = 1.0\n",
               "3: 'solver.seed' must be an integer, not a real number"},
        BadJob{"ToleranceOne", "[solver]\ntolerance = 1\n",
               "3: 'solver.tolerance' must be in (0, 1), got 1"},
        BadJob{"ToleranceNan", "[solver]\ntolerance = nan\n",
               "3: 'solver.tolerance' must be finite"},
        BadJob{"NegativeRays", "[solver]\nrays = -5\n", "3: 'solver.rays' must be >= 0, got -5"},
        BadJob{"NegativeSeconds", "[solver]\nseconds = -1\n",
               "3: 'solver.seconds' must be >= 0, got -1"},
        BadJob{"ZeroShotRays", "[solver]\nshot_rays = 0\n",
               "3: 'solver.shot_rays' must be >= 1, got 0"},
        BadJob{"ZeroMinShooterRays", "[solver]\nmin_shooter_rays = 0\n",
               "3: 'solver.min_shooter_rays' must be in [1, 4294967295], got 0"},
        BadJob{"ShootersPerRoundTooBig", "[solver]\nshooters_per_round = 4294967296\n",
               "3: 'solver.shooters_per_round' must be in [0, 4294967295], got 4294967296"},
        BadJob{"OverrelaxationTwo", "[solver]\noverrelaxation = 2\n",
               "3: 'solver.overrelaxation' must be in [1, 2), got 2"},
        BadJob{"OverrelaxationBelowOne", "[solver]\noverrelaxation = 0.9\n",
               "3: 'solver.overrelaxation' must be in [1, 2), got 0.9"},
        BadJob{"OverrelaxationNan", "[solver]\noverrelaxation = nan\n",
               "3: 'solver.overrelaxation' must be finite"},
        BadJob{"OverrelaxationString", "[solver]\noverrelaxation = \"1.2\"\n",
               "3: 'solver.overrelaxation' must be a number, not a string"},
        BadJob{"GridStepTooBig", "[solver]\ngrid_step_degrees = 91\n",
               "3: 'solver.grid_step_degrees' must be in (0, 90], got 91"},
        BadJob{"TooManyThreads", "[solver]\nthreads = 100000\n",
               "3: 'solver.threads' must be in [0, 65536], got 100000"},
        BadJob{"Fov180", "[camera]\nfov = 180\n", "3: 'camera.fov' must be in (0, 180), got 180"},
        BadJob{"WidthZero", "[camera]\nwidth = 0\n",
               "3: 'camera.width' must be in [1, 16384], got 0"},
        BadJob{"HeightTooBig", "[camera]\nheight = 16385\n",
               "3: 'camera.height' must be in [1, 16384], got 16385"},
        BadJob{"ZeroSamples", "[camera]\nsamples_per_pixel = 0\n",
               "3: 'camera.samples_per_pixel' must be in [1, 1024], got 0"},
        BadJob{"EyeTwoNumbers", "[camera]\neye = [1, 2]\ntarget = [0, 0, 0]\n",
               "3: 'camera.eye' must be an array of 3 finite numbers, e.g. [0, 1, 0]"},
        BadJob{"EyeWithString", "[camera]\neye = [1, 2, \"3\"]\n",
               "3: 'camera.eye' must be an array of 3 finite numbers, e.g. [0, 1, 0]"},
        BadJob{"EyeWithoutTarget", "[camera]\neye = [0, 0, -5]\n",
               "3: 'camera.eye' is set without 'camera.target'; set both or neither"},
        BadJob{"TargetWithoutEye", "[camera]\ntarget = [0, 0, -5]\n",
               "3: 'camera.target' is set without 'camera.eye'; set both or neither"},
        BadJob{"EyeEqualsTarget", "[camera]\neye = [1, 1, 1]\ntarget = [1, 1, 1]\n",
               "3: 'camera.eye' must differ from camera.target"},
        BadJob{"UnknownOutputKey", "[output]\nlightmap = 64\n", "3: unknown key 'output.lightmap'"},
        BadJob{"LightmapSizeTooSmall", "[output]\nlightmap_size = 8\n",
               "3: 'output.lightmap_size' must be 0 (automatic) or in [16, 8192], got 8"},
        BadJob{"LightmapSizeTooBig", "[output]\nlightmap_size = 8193\n",
               "3: 'output.lightmap_size' must be 0 (automatic) or in [16, 8192], got 8193"},
        BadJob{"LightmapSizeNegative", "[output]\nlightmap_size = -64\n",
               "3: 'output.lightmap_size' must be 0 (automatic) or in [16, 8192], got -64"},
        BadJob{"LightmapSizeReal", "[output]\nlightmap_size = 64.0\n",
               "3: 'output.lightmap_size' must be an integer, not a real number"},
        BadJob{"LightmapSizeString", "[output]\nlightmap_size = \"1k\"\n",
               "3: 'output.lightmap_size' must be an integer, not a string"},
        BadJob{"LightmapTexelZero", "[output]\nlightmap_texel = 0\n",
               "3: 'output.lightmap_texel' must be > 0, got 0"},
        BadJob{"LightmapTexelString", "[output]\nlightmap_texel = \"1cm\"\n",
               "3: 'output.lightmap_texel' must be a number, not a string"},
        BadJob{"LightmapSizeAndTexel", "[output]\nlightmap_size = 64\nlightmap_texel = 0.1\n",
               "4: 'output.lightmap_texel' is set with 'output.lightmap_size'; set one or the "
               "other"},
        BadJob{"OutputNotATable", "output = 64\n", "2: 'output' must be a table, not an integer"},
        BadJob{"UpAlongView", "[camera]\neye = [0, 0, 0]\ntarget = [0, 0, 1]\nup = [0, 0, 2]\n",
               "5: 'camera.up' must be nonzero and not parallel to camera.target - camera.eye"}));

}  // namespace
}  // namespace radfarm
