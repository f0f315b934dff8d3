// `radfarm render` end to end: outputs, byte-identical results across thread counts, closed-scene
// and furnace checks. Runs the real binary.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "cli/exit_codes.h"
#include "core/thread_pool.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"
#include "tests/cli/shipped_scenes.h"

namespace radfarm {
namespace {

using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

const std::string kScenes = RADFARM_SOURCE_DIR "/scenes/";

testing::CommandResult Render(const std::string& scene, const std::string& out,
                              std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {RADFARM_CLI_PATH, "render", kScenes + scene, "--out", out};
  args.insert(args.end(), extra.begin(), extra.end());
  return RunCommand(args);
}

// The number after "key": in a flat JSON object.
double JsonNumber(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return NAN;
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

// The files of two renders sharing one --db store: the first solves, the second finds its job.
struct RenderFiles {
  std::string patches_csv;
  std::string stats_json;
};
void RenderTwiceWithDb(const std::string& scene, std::vector<std::string> settings,
                       std::vector<RenderFiles>* runs) {
  TempDir store;
  settings.insert(settings.end(), {"--db", store.File("render.db")});
  for (const char* run : {"first", "again"}) {
    SCOPED_TRACE(run);
    TempDir dir;
    const auto d = Render(scene, dir.path(), settings);
    ASSERT_EQ(d.exit_code, kExitOk) << d.err;
    runs->push_back({ReadFile(dir.File("patches.csv")), ReadFile(dir.File("stats.json"))});
  }
}

std::vector<std::vector<std::string>> ReadCsv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(ReadFile(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream cell_stream(line);
    for (std::string cell; std::getline(cell_stream, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(RenderCommandTest, CornellBoxWritesEveryOutput) {
  TempDir out;
  const auto r = Render("cornell-box.toml", out.path(), {"--tolerance", "0.01"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(ReadFile(out.File("image.png")).substr(1, 3), "PNG");
  EXPECT_EQ(ReadFile(out.File("image.exr")).substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
  EXPECT_EQ(ReadFile(out.File("radiosity.ply")).substr(0, 4), "ply\n");
  const auto csv = ReadCsv(out.File("patches.csv"));
  ASSERT_GT(csv.size(), 1u);
  EXPECT_EQ(ReadFile(out.File("patches.csv")).substr(0, 45),
            "patch,surface,material,area,cx,cy,cz,nx,ny,nz");
  const std::string stats = ReadFile(out.File("stats.json"));
  for (const char* key : {"rays", "rounds", "seconds", "rays_per_second", "patches",
                          "unshot_fraction", "escaped_rays", "threads", "seed"}) {
    EXPECT_TRUE(std::isfinite(JsonNumber(stats, key))) << key << " in " << stats;
  }
  EXPECT_NE(stats.find("\"sampler\": \"sobol\""), std::string::npos) << stats;
  EXPECT_EQ(JsonNumber(stats, "patches"), double(csv.size() - 1));
  EXPECT_LE(JsonNumber(stats, "unshot_fraction"), 0.01);
  // What the scene's size got, in stats.json and on the terminal (core/solve_rules.h): the start
  // and the display were skipped above some size with no word.
  EXPECT_EQ(JsonNumber(stats, "direct_start_used"), 1) << stats;
  EXPECT_EQ(JsonNumber(stats, "display_at_points"), 1) << stats;
  EXPECT_NE(stats.find("\"direct_start\": \"from the direct light of 30 emitter patches"),
            std::string::npos)
      << stats;
  EXPECT_NE(stats.find("\"display\": \"at its own points: "), std::string::npos) << stats;
  EXPECT_NE(r.out.find("\ndirect light: from the direct light of 30 emitter patches"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\ndisplay: at its own points: "), std::string::npos) << r.out;
  // The closing line counts the display: its seconds and the whole command's.
  EXPECT_NE(r.out.find("), the display and files in "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" s in all; wrote "), std::string::npos) << r.out;
  // Where the time went: each phase, its wall and CPU seconds, in stats.json and a closing line.
  for (const char* phase : {"meshing", "direct light", "rounds", "gather", "display", "outputs"}) {
    EXPECT_NE(stats.find(std::string("{\"phase\": \"") + phase +
                         "\", \"where\": \"render\", "
                         "\"wall_seconds\": "),
              std::string::npos)
        << phase << " in " << stats;
  }
  EXPECT_NE(r.out.find("\ntime: meshing "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(", display "), std::string::npos) << r.out;
  // Every patch lit, nothing negative or NaN.
  for (size_t i = 1; i < csv.size(); ++i) {
    ASSERT_EQ(csv[i].size(), 13u);
    for (int c = 10; c < 13; ++c) {
      const double v = std::strtod(csv[i][c].c_str(), nullptr);
      ASSERT_TRUE(std::isfinite(v) && v >= 0) << "row " << i;
    }
  }
}

// Outputs that cannot be written (directories where image.png and patches.csv go) cost those files
// only: the others are written, each failure is named on a line of its own (not just the first),
// and the exit is non-zero.
TEST(RenderCommandTest, UnwritableOutputsLeaveTheOthersWrittenAndAreEachNamed) {
  TempDir out;
  std::filesystem::create_directories(out.File("image.png"));
  std::filesystem::create_directories(out.File("patches.csv"));
  const auto r = Render("cornell-box.toml", out.path(), {"--tolerance", "0.05", "-q"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  for (const char* file : {"image.png", "patches.csv"}) {
    EXPECT_NE(r.err.find("radfarm: " + out.File(file)), std::string::npos) << r.err;
  }
  for (const char* file : {"image.exr", "radiosity.ply", "lit.glb", "stats.json"}) {
    EXPECT_FALSE(ReadFile(out.File(file)).empty()) << file;
  }
}

// A job file in `dir` rendering the Cornell box coarsely with one illuminance plane over the floor.
std::string IlluminanceJob(const TempDir& dir, const std::string& surfaces) {
  const std::string path = dir.File("planes.toml");
  std::ofstream(path) << "scene = \"" << kScenes << "cornell-box.obj\"\n[mesh]\npatch_size = 60\n"
                      << "[solver]\ntolerance = 0.05\n[[illuminance]]\nname = \"floor\"\n"
                      << "height = 100\nspacing = 50\nsurfaces = [" << surfaces << "]\n";
  return path;
}

// Hostile scenes, threads: a job file saying threads = 65536 made `render` start 65536 threads.
// Without --threads it runs on this machine's cores at most; --threads still chooses.
TEST(RenderCommandTest, AJobFileAsking65536ThreadsRunsOnThisMachinesCores) {
  TempDir jobs;
  const std::string job = jobs.File("greedy.toml");
  std::ofstream(job) << "scene = \"" << kScenes << "cornell-box.obj\"\n[mesh]\npatch_size = 60\n"
                     << "[solver]\ntolerance = 0.2\nthreads = 65536\n[camera]\nwidth = 64\n"
                     << "height = 64\n";
  for (const auto& [extra, threads] : std::vector<std::pair<std::vector<std::string>, double>>{
           {{}, double(MachineThreads())}, {{"--threads", "3"}, 3.0}}) {
    TempDir out;
    std::vector<std::string> args = {RADFARM_CLI_PATH, "render", job, "--out", out.path(), "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = RunCommand(args);
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    EXPECT_EQ(JsonNumber(ReadFile(out.File("stats.json")), "threads"), threads);
  }
}

// The illuminance report is part of the determinism contract: the thread count changes no byte.
TEST(RenderCommandTest, TheIlluminanceReportIsTheSameOnAnyThreads) {
  TempDir jobs;
  const std::string job = IlluminanceJob(jobs, "\"floor\"");
  std::string reference;
  for (const char* threads : {"1", "2"}) {
    TempDir out;
    const auto r = RunCommand(
        {RADFARM_CLI_PATH, "render", job, "--out", out.path(), "--threads", threads, "-q"});
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    const std::string report = ReadFile(out.File("illuminance.json")) +
                               ReadFile(out.File("illuminance/floor.csv")) +
                               ReadFile(out.File("illuminance/floor.png"));
    ASSERT_NE(ReadFile(out.File("illuminance/floor.csv")).find("x,y,z,lux\n"), std::string::npos);
    if (reference.empty()) {
      reference = report;
    } else {
      EXPECT_TRUE(report == reference) << "--threads " << threads << " differs";
    }
  }
}

// The IES example job: four downlights from a manufacturer's file light a room that emits nothing.
// Every output is written, and the patches and the work plane's report are the same bytes on one
// thread and two.
TEST(RenderCommandTest, TheIesDownlightsJobWritesItsOutputsTheSameOnAnyThreads) {
  std::string reference;
  for (const char* threads : {"1", "2"}) {
    TempDir out;
    const auto r =
        Render("ies-downlights.toml", out.path(), {"--threads", threads, "--rays", "400000", "-q"});
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    for (const char* file :
         {"image.png", "patches.csv", "stats.json", "lit.glb", "illuminance.json",
          "illuminance/workplane.csv", "illuminance/workplane.png"}) {
      EXPECT_FALSE(ReadFile(out.File(file)).empty()) << file;
    }

    // Four 2100 lm downlights 2.2 m above the plane: some hundreds of lux under them.
    const std::vector<std::vector<std::string>> rows =
        ReadCsv(out.File("illuminance/workplane.csv"));
    ASSERT_GT(rows.size(), 10u);
    double most = 0;
    for (size_t i = 1; i < rows.size(); ++i) most = std::max(most, std::stod(rows[i].back()));
    EXPECT_GT(most, 200);
    EXPECT_LT(most, 2000);
    const std::string run = ReadFile(out.File("patches.csv")) +
                            ReadFile(out.File("illuminance.json")) +
                            ReadFile(out.File("illuminance/workplane.csv"));
    if (reference.empty()) {
      reference = run;
    } else {
      EXPECT_TRUE(run == reference) << "--threads " << threads << " differs";
    }
  }
}

// A plane whose surfaces name nothing in the scene costs its report only, named on its own line.
TEST(RenderCommandTest, AnIlluminancePlaneNamingNothingFailsAloneAndSaysWhy) {
  TempDir jobs, out;
  const auto r = RunCommand(
      {RADFARM_CLI_PATH, "render", IlluminanceJob(jobs, "\"Desk*\""), "--out", out.path(), "-q"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("illuminance plane 'floor': 'Desk*' names no object and no material"),
            std::string::npos)
      << r.err;
  for (const char* file : {"image.png", "patches.csv", "stats.json"}) {
    EXPECT_FALSE(ReadFile(out.File(file)).empty()) << file;
  }
  EXPECT_TRUE(ReadFile(out.File("illuminance.json")).empty());
}

// A ray budget covers the direct light and the display too: the start's shadow rays
// (stats.json start_rays) are planned to a quarter of it, the display's rays (display_rays) to
// another, and the rounds get the rest less the display's quarter, exactly.
TEST(RenderCommandTest, ARayBudgetCountsTheDirectLightsShadowRays) {
  TempDir out;
  const auto r = Render("cornell-box.toml", out.path(), {"--rays", "400000", "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::string stats = ReadFile(out.File("stats.json"));
  const double start = JsonNumber(stats, "start_rays");
  EXPECT_GT(start, 0) << stats;
  EXPECT_LE(start, 400000 / 4) << stats;
  EXPECT_EQ(JsonNumber(stats, "rays") + start, 400000 - 400000 / 4) << stats;
  // The start's time, apart from the rounds' (bench/budget reads it).
  EXPECT_GT(JsonNumber(stats, "start_seconds"), 0) << stats;
  EXPECT_LE(JsonNumber(stats, "start_seconds"), JsonNumber(stats, "seconds")) << stats;
  const double display = JsonNumber(stats, "display_rays");
  EXPECT_GT(display, 0) << stats;
  EXPECT_LE(display, 400000 / 4) << stats;
  EXPECT_NE(stats.find("\"stop_reason\": \"ray budget\""), std::string::npos) << stats;
}

// A time budget that leaves no time for a round after what follows the solve still writes the
// outputs (the direct light), and says why there is no bounced light.
TEST(RenderCommandTest, ATimeBudgetTooSmallForARoundSaysSo) {
  TempDir out;
  const auto r = Render("cornell-box.toml", out.path(), {"--seconds", "0.2", "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_NE(r.err.find("--seconds 0.2 left no time for a round"), std::string::npos) << r.err;
  const std::string stats = ReadFile(out.File("stats.json"));
  EXPECT_EQ(JsonNumber(stats, "rounds"), 0) << stats;
  EXPECT_NE(stats.find("\"stop_reason\": \"time budget\""), std::string::npos) << stats;
  EXPECT_TRUE(std::filesystem::exists(out.File("image.png")));
  // A budget with room for rounds says nothing of the kind.
  TempDir roomy;
  const auto ok = Render("cornell-box.toml", roomy.path(), {"--seconds", "30", "-q"});
  ASSERT_EQ(ok.exit_code, kExitOk) << ok.err;
  EXPECT_EQ(ok.err.find("left no time"), std::string::npos) << ok.err;
}

// The determinism contract end to end: thread count never changes a byte of patches.csv.
TEST(RenderCommandTest, ThreadCountGivesByteIdenticalPatches) {
  std::string reference;
  for (const char* threads : {"1", "2", "7"}) {
    TempDir out;
    const auto r =
        Render("cornell-box.obj", out.path(), {"--threads", threads, "--tolerance", "0.01", "-q"});
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    const std::string csv = ReadFile(out.File("patches.csv"));
    ASSERT_GT(csv.size(), 1000u);
    if (reference.empty()) {
      reference = csv;
    } else {
      EXPECT_TRUE(csv == reference) << "--threads " << threads << " differs";
    }
  }
}

// Adaptive refinement end to end: stats.json reports the patch counts before and after, the
// refined mesh is what patches.csv lists, and the thread count changes no byte of it.
TEST(RenderCommandTest, AdaptiveRefinementIsReportedAndDeterministic) {
  std::string reference;
  for (const char* threads : {"1", "2"}) {
    TempDir out;
    const auto r = Render("cornell-box-adaptive.toml", out.path(),
                          {"--threads", threads, "--tolerance", "0.2", "-q"});
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    const std::string stats = ReadFile(out.File("stats.json"));
    const std::string csv = ReadFile(out.File("patches.csv"));
    const double before = JsonNumber(stats, "patches_before_refinement");
    const double after = JsonNumber(stats, "patches_after_refinement");
    // cornell-box.obj at patch size 25, the ceiling above the light cut along its outline
    EXPECT_EQ(before, 3852) << stats;
    EXPECT_GT(after, before) << stats;
    EXPECT_EQ(JsonNumber(stats, "patches"), after) << stats;
    EXPECT_EQ(double(ReadCsv(out.File("patches.csv")).size() - 1), after);
    if (reference.empty()) {
      reference = csv;
    } else {
      EXPECT_TRUE(csv == reference) << "--threads " << threads << " differs";
    }
  }
  TempDir plain;
  const auto r = Render("cornell-box.obj", plain.path(), {"--rays", "20000", "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::string stats = ReadFile(plain.File("stats.json"));
  EXPECT_EQ(JsonNumber(stats, "patches_before_refinement"), JsonNumber(stats, "patches"));
  EXPECT_EQ(JsonNumber(stats, "patches_after_refinement"), JsonNumber(stats, "patches"));
}

// --db keeps a refining render's rounds (with its refined mesh) and gives the files a render
// without --db gives; run again on the finished job, it writes them again from the checkpoint.
// (tests/farm/render_resume_test.cc kills one midway.)
TEST(RenderCommandTest, AdaptiveRefinementWithDbMatchesPlainRender) {
  // Past the first refinement point (a restart on the refined mesh), then a ray budget that the
  // capped last round does not spend to the ray: run again, the finished job runs no more rounds.
  const std::vector<std::string> settings = {"--tolerance",  "0.05", "--rays", "3000000",
                                             "--patch-size", "50",   "-q"};
  TempDir plain;
  const auto r = Render("cornell-box-adaptive.toml", plain.path(), settings);
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::string reference = ReadFile(plain.File("patches.csv"));
  const std::string reference_stats = ReadFile(plain.File("stats.json"));
  std::vector<RenderFiles> runs;
  ASSERT_NO_FATAL_FAILURE(RenderTwiceWithDb("cornell-box-adaptive.toml", settings, &runs));
  for (size_t run = 0; run < runs.size(); ++run) {
    SCOPED_TRACE(run == 0 ? "first" : "again");
    EXPECT_TRUE(runs[run].patches_csv == reference);
    const std::string& stats = runs[run].stats_json;
    for (const char* key : {"patches_before_refinement", "patches_after_refinement", "rays",
                            "rounds", "unshot_fraction"}) {
      EXPECT_EQ(JsonNumber(stats, key), JsonNumber(reference_stats, key)) << key;
    }
  }
  EXPECT_GT(JsonNumber(reference_stats, "patches_after_refinement"),
            JsonNumber(reference_stats, "patches_before_refinement"));
}

// A render stopped by a capped round that left some of the budget unspent (the grid's shots cannot
// be cut, so its capped round drops whole shots; proportional shots spend a budget exactly): run
// again on its finished job, it runs no further round and writes the same files (it used to plan
// one more).
TEST(RenderCommandTest, BudgetStoppedDbRenderRerunsIdentically) {
  const std::vector<std::string> settings = {"--rays", "2900001", "--sampler", "grid", "-q"};
  TempDir plain;
  ASSERT_EQ(Render("cornell-box.toml", plain.path(), settings).exit_code, kExitOk);
  const std::string reference = ReadFile(plain.File("patches.csv"));
  const std::string reference_stats = ReadFile(plain.File("stats.json"));
  ASSERT_LT(JsonNumber(reference_stats, "rays"), 2900001);
  std::vector<RenderFiles> runs;
  ASSERT_NO_FATAL_FAILURE(RenderTwiceWithDb("cornell-box.toml", settings, &runs));
  for (size_t run = 0; run < runs.size(); ++run) {
    SCOPED_TRACE(run == 0 ? "first" : "again");
    EXPECT_TRUE(runs[run].patches_csv == reference);
    const std::string& stats = runs[run].stats_json;
    EXPECT_EQ(JsonNumber(stats, "rays"), JsonNumber(reference_stats, "rays"));
    EXPECT_EQ(JsonNumber(stats, "rounds"), JsonNumber(reference_stats, "rounds"));
    EXPECT_NE(stats.find("\"stop_reason\": \"ray budget\""), std::string::npos) << stats;
  }
}

// A closed furnace with Ke 1 and Kd 0.9 reads 10 on every patch: B = E / (1 - rho).
TEST(RenderCommandTest, FurnaceReadsTen) {
  TempDir out;
  const auto r = Render("furnace.obj", out.path(), {"--patch-size", "0.25", "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const auto csv = ReadCsv(out.File("patches.csv"));
  ASSERT_GT(csv.size(), 6u);
  for (size_t i = 1; i < csv.size(); ++i) {
    // Stopping at unshot 0.1 % leaves B 0.1 % low; ray noise adds about 0.5 % per patch here.
    for (int c = 10; c < 13; ++c) EXPECT_NEAR(std::strtod(csv[i][c].c_str(), nullptr), 10.0, 0.2);
  }
  EXPECT_EQ(JsonNumber(ReadFile(out.File("stats.json")), "escaped_rays"), 0);
}

TEST(RenderCommandTest, ClosedCornellBoxLeaksNoRays) {
  TempDir out;
  const auto r = Render("cornell-box-closed.obj", out.path(), {"--tolerance", "0.02", "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::string stats = ReadFile(out.File("stats.json"));
  EXPECT_EQ(JsonNumber(stats, "escaped_rays"), 0) << stats;
  // Back-face hits come only from floor patches that straddle a block's footprint: their rays from
  // the covered part start inside the block (absorbed there). A small fraction of the rays.
  EXPECT_LT(JsonNumber(stats, "backface_hits"), 0.01 * JsonNumber(stats, "rays")) << stats;
}

// Two boxes touching face to face: the contact faces are dropped (with a warning), so no light
// passes through the contact and no ray ever gets inside a box.
TEST(RenderCommandTest, TouchingBoxesLetNoLightThroughTheContact) {
  TempDir out;
  const auto r = Render("touching-boxes.obj", out.path(), {"--tolerance", "0.01", "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_NE(r.err.find("hidden inside a coplanar overlap"), std::string::npos) << r.err;
  const std::string stats = ReadFile(out.File("stats.json"));
  // The two contact faces and the two box bottoms standing on the floor.
  EXPECT_EQ(JsonNumber(stats, "dropped_hidden_faces"), 4) << stats;
  EXPECT_EQ(JsonNumber(stats, "escaped_rays"), 0) << stats;
  // No patch is left on the contact square (x = 1.5, y in [0, 1], z in [1.5, 2.5]) to pass light.
  const auto csv = ReadCsv(out.File("patches.csv"));
  for (size_t i = 1; i < csv.size(); ++i) {
    const double cx = std::strtod(csv[i][4].c_str(), nullptr);
    const double cy = std::strtod(csv[i][5].c_str(), nullptr);
    const double cz = std::strtod(csv[i][6].c_str(), nullptr);
    const double nx = std::strtod(csv[i][7].c_str(), nullptr);
    const bool on_contact = std::abs(cx - 1.5) < 1e-9 && std::abs(std::abs(nx) - 1) < 1e-9 &&
                            cy > 0 && cy < 1 && cz > 1.5 && cz < 2.5;
    EXPECT_FALSE(on_contact) << "patch " << csv[i][0] << " lies on the contact";
  }
}

TEST(RenderCommandTest, RayBudgetAndSeedAreHonoured) {
  TempDir a, b;
  ASSERT_EQ(Render("furnace.obj", a.path(), {"--rays", "50000", "--seed", "5", "-q"}).exit_code, 0);
  ASSERT_EQ(Render("furnace.obj", b.path(), {"--rays", "50000", "--seed", "6", "-q"}).exit_code, 0);
  const std::string stats = ReadFile(a.File("stats.json"));
  EXPECT_EQ(JsonNumber(stats, "seed"), 5);
  EXPECT_NE(stats.find("ray budget"), std::string::npos) << stats;
  EXPECT_NE(ReadFile(a.File("patches.csv")), ReadFile(b.File("patches.csv")));
}

}  // namespace
}  // namespace radfarm

namespace radfarm {
namespace {

// Every scene and job file shipped in scenes/ renders end to end (a small ray budget keeps it
// quick).
TEST(RenderCommandTest, EveryShippedSceneRenders) {
  int rendered = 0;
  // An OBJ lit only by a job's IES lamps renders through its job.
  const std::set<std::filesystem::path> lamp_lit = testing::ScenesLitByJobLamps(kScenes);
  EXPECT_FALSE(lamp_lit.empty()) << "ies-downlights.toml lights its OBJ";
  for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".obj" && ext != ".toml") continue;
    if (lamp_lit.contains(std::filesystem::weakly_canonical(entry.path()))) continue;
    TempDir out;
    const auto r = RunCommand({RADFARM_CLI_PATH, "render", entry.path().string(), "--out",
                               out.path(), "--rays", "20000", "-q"});
    EXPECT_EQ(r.exit_code, kExitOk) << entry.path() << ": " << r.err;
    EXPECT_FALSE(ReadFile(out.File("patches.csv")).empty()) << entry.path();
    ++rendered;
  }
  EXPECT_GE(rendered, 10);
}

}  // namespace
}  // namespace radfarm
