// `radfarm fetch` against a fake master serving a job solution made here by the same Solve()
// `radfarm render` runs: the six files, byte-identical to render's (stats.json aside), and the
// ways a solution can be unusable.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "cli/exit_codes.h"
#include "cli/job_inputs.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/patch_scene_codec.h"
#include "codec/solution_display.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"
#include "tests/cli/control_fixtures.h"
#include "tests/cli/fake_control_server.h"

namespace radfarm {
namespace {

using nlohmann::json;
using testing::ControlAnswer;
using testing::ControlRequest;
using testing::FakeControlServer;
using testing::JobObject;
using testing::OkAnswer;
using testing::ReadFile;
using testing::RunCommand;
using testing::RunFarm;
using testing::TempDir;

const std::string kCornell = RADFARM_SOURCE_DIR "/scenes/cornell-box.toml";
// A short solve: few patches, loose tolerance.
const char* const kTolerance = "0.05";
const char* const kPatchSize = "60";

class FetchCommandTest : public ::testing::Test {
 protected:
  // The job `render kCornell --tolerance kTolerance --patch-size kPatchSize` solves, solved on
  // first use.
  static const codec::JobSolution& Solution() {
    static const codec::JobSolution solution = [] {
      JobOverrides overrides;
      overrides.tolerance = std::stod(kTolerance);
      overrides.patch_size = std::stod(kPatchSize);
      std::vector<std::string> warnings;
      Result<LoadedJob> job = LoadJobForSolve(kCornell, overrides, &warnings);
      if (!job.ok()) throw std::runtime_error(job.error());
      const SolveResult solved = Solve(job->mesh.patch_scene(), job->job.solver);
      return codec::JobSolution{codec::EncodeJobBundle({job->job, job->scene}),
                                solved.radiosity,
                                solved.unshot,
                                solved.stats,
                                {},
                                {}};
    }();
    return solution;
  }

  static ControlAnswer Serve(const codec::JobSolution& solution) {
    ControlAnswer answer = OkAnswer({{"job", JobObject(5, "done", 7)}});
    answer.attachment = codec::EncodeJobSolution(solution);
    return answer;
  }

  // Runs fetch of job 5 against a master answering `answer`.
  static testing::CommandResult Fetch(const ControlAnswer& answer, const std::string& out,
                                      std::vector<std::string> extra = {}) {
    FakeControlServer server([answer](const ControlRequest&) { return answer; });
    std::vector<std::string> args = {"fetch", "5", "--out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return RunFarm(server.socket_path(), args);
  }

  TempDir dir_;
};

TEST_F(FetchCommandTest, WritesTheFilesRenderWritesByteForByte) {
  FakeControlServer server([](const ControlRequest&) { return Serve(Solution()); });
  const std::string fetched = dir_.File("fetched/nested");
  const auto r = RunFarm(server.socket_path(), {"fetch", "5", "--out", fetched});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(server.requests()[0].body, json({{"command", "fetch"}, {"id", 5}}));
  EXPECT_EQ(r.out, "job 5 (job-5, done, round 7): wrote " + fetched + "\n");

  const std::string rendered = dir_.File("rendered");
  const auto render = RunCommand({RADFARM_CLI_PATH, "render", kCornell, "--tolerance", kTolerance,
                                  "--patch-size", kPatchSize, "--quiet", "--out", rendered});
  ASSERT_EQ(render.exit_code, kExitOk) << render.err;
  for (const char* file : {"patches.csv", "image.png", "image.exr", "radiosity.ply", "lit.glb"}) {
    const std::string mine = ReadFile(fetched + "/" + file);
    EXPECT_FALSE(mine.empty()) << file;
    EXPECT_TRUE(mine == ReadFile(rendered + "/" + file)) << file << " differs from render's";
  }
  const json stats = json::parse(ReadFile(fetched + "/stats.json"), nullptr, false);
  ASSERT_TRUE(stats.is_object()) << ReadFile(fetched + "/stats.json");
  EXPECT_EQ(stats["rays"], Solution().stats.rays);
  EXPECT_EQ(stats["rounds"], Solution().stats.rounds);
  EXPECT_EQ(stats["stop_reason"], Solution().stats.stop_reason);
}

TEST_F(FetchCommandTest, WritesTheLightmapsRenderWrites) {
  // The room with a second UV map: the bundle carries the UVs and the lightmap size, so fetch
  // bakes the same lightmaps, at the automatic sizes and at a size chosen on the command line.
  const std::string job_file = RADFARM_SOURCE_DIR "/tests/blender/lightmap-room.toml";
  std::string automatic_table;
  for (const uint32_t size : {0u, 40u}) {
    SCOPED_TRACE(size);
    JobOverrides overrides;
    std::vector<std::string> extra;
    if (size > 0) {
      overrides.lightmap_size = size;
      extra = {"--lightmap-size", std::to_string(size)};
    }
    std::vector<std::string> warnings;
    Result<LoadedJob> job = LoadJobForSolve(job_file, overrides, &warnings);
    ASSERT_TRUE(job.ok()) << job.error();
    const SolveResult solved = Solve(job->mesh.patch_scene(), job->job.solver);
    const codec::JobSolution solution{codec::EncodeJobBundle({job->job, job->scene}),
                                      solved.radiosity,
                                      solved.unshot,
                                      solved.stats,
                                      {},
                                      {}};
    const std::string fetched = dir_.File("fetched" + std::to_string(size));
    const auto r = Fetch(Serve(solution), fetched);
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    const std::string rendered = dir_.File("rendered" + std::to_string(size));
    std::vector<std::string> args = {RADFARM_CLI_PATH, "render", job_file,
                                     "--quiet",        "--out",  rendered};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto render = RunCommand(args);
    ASSERT_EQ(render.exit_code, kExitOk) << render.err;
    for (const char* file : {"lit.glb", "lightmaps/Room.exr", "lightmaps/Floor.exr",
                             "lightmaps/Table.exr", "lightmaps/Table.png"}) {
      const std::string mine = ReadFile(fetched + "/" + file);
      EXPECT_FALSE(mine.empty()) << file;
      EXPECT_TRUE(mine == ReadFile(rendered + "/" + file)) << file << " differs from render's";
    }
    const std::string table = ReadFile(fetched + "/lightmaps/Table.png");
    if (size == 0) {
      automatic_table = table;
      continue;
    }
    EXPECT_NE(table, automatic_table);
    // The PNG's IHDR: width and height, big-endian, at bytes 16 and 20.
    ASSERT_GE(table.size(), 24u);
    for (size_t at : {size_t{16}, size_t{20}}) {
      uint32_t side = 0;
      for (size_t k = 0; k < 4; ++k) side = side << 8 | uint8_t(table[at + k]);
      EXPECT_EQ(side, size) << "at byte " << at;
    }
  }
}

// The bundle carries the job's illuminance planes, so fetch writes the report render writes, from
// the same solution the same bytes.
TEST_F(FetchCommandTest, WritesTheIlluminanceReportRenderWrites) {
  const std::string job_file = dir_.File("planes.toml");
  std::ofstream(job_file) << "scene = \"" RADFARM_SOURCE_DIR "/scenes/cornell-box.obj\"\n"
                          << "[mesh]\npatch_size = 60\n[solver]\ntolerance = 0.05\n"
                          << "[[illuminance]]\nname = \"floor\"\nheight = 100\nspacing = 50\n";
  std::vector<std::string> warnings;
  Result<LoadedJob> job = LoadJobForSolve(job_file, {}, &warnings);
  ASSERT_TRUE(job.ok()) << job.error();
  const SolveResult solved = Solve(job->mesh.patch_scene(), job->job.solver);
  const codec::JobSolution solution{codec::EncodeJobBundle({job->job, job->scene}),
                                    solved.radiosity,
                                    solved.unshot,
                                    solved.stats,
                                    {},
                                    {}};
  const std::string fetched = dir_.File("fetched");
  const auto r = Fetch(Serve(solution), fetched);
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::string rendered = dir_.File("rendered");
  const auto render =
      RunCommand({RADFARM_CLI_PATH, "render", job_file, "--quiet", "--out", rendered});
  ASSERT_EQ(render.exit_code, kExitOk) << render.err;
  for (const char* file : {"illuminance.json", "illuminance/floor.csv", "illuminance/floor.png"}) {
    const std::string mine = ReadFile(fetched + "/" + file);
    EXPECT_FALSE(mine.empty()) << file;
    EXPECT_TRUE(mine == ReadFile(rendered + "/" + file)) << file << " differs from render's";
  }
  const json report = json::parse(ReadFile(fetched + "/illuminance.json"), nullptr, false);
  ASSERT_TRUE(report.is_object());
  const json& floor = report["planes"][0];
  EXPECT_EQ(floor["name"], "floor");
  // The floor is about 556 x 559: 11 x 11 cells of 50, of which those wholly on it.
  EXPECT_GE(floor["points"].get<int>(), 81);
  EXPECT_GT(floor["min"].get<double>(), 0);
  EXPECT_LT(floor["min"].get<double>(), floor["mean"].get<double>());
  EXPECT_LT(floor["mean"].get<double>(), floor["max"].get<double>());
}

TEST_F(FetchCommandTest, WritesTheDisplayTheMasterDrewWithoutDrawingIt) {
  // The master's display of the same solution: the files of the test above, and no display
  // progress, since nothing is drawn here.
  codec::JobSolution drawn = Solution();
  Result<std::vector<uint8_t>> display = codec::DrawEncodedDisplay(drawn);
  ASSERT_TRUE(display.ok()) << display.error();
  drawn.display = std::move(*display);
  const std::string with = dir_.File("with"), without = dir_.File("without");
  auto r = Fetch(Serve(drawn), with);
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.out, "job 5 (job-5, done, round 7): wrote " + with + "\n");
  r = Fetch(Serve(Solution()), without);
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  for (const char* file : {"patches.csv", "image.png", "image.exr", "radiosity.ply", "lit.glb"}) {
    EXPECT_TRUE(ReadFile(with + "/" + file) == ReadFile(without + "/" + file)) << file;
  }

  // The carried display is the one written: drawn from twice the light, the image differs.
  codec::JobSolution brighter = Solution();
  for (Rgb& b : brighter.radiosity) b = b * 2.0;
  Result<std::vector<uint8_t>> other = codec::DrawEncodedDisplay(brighter);
  ASSERT_TRUE(other.ok()) << other.error();
  codec::JobSolution carried = Solution();
  carried.display = std::move(*other);
  const std::string bright = dir_.File("bright");
  r = Fetch(Serve(carried), bright);
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_FALSE(ReadFile(bright + "/image.png") == ReadFile(without + "/image.png"));
  EXPECT_TRUE(ReadFile(bright + "/patches.csv") == ReadFile(without + "/patches.csv"));
}

TEST_F(FetchCommandTest, DamagedDisplayFails) {
  codec::JobSolution damaged = Solution();
  damaged.display = {1, 2, 3, 4, 5, 6, 7, 8};
  const auto r = Fetch(Serve(damaged), dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("radfarm: job 5: the display in the solution: "), std::string::npos)
      << r.err;
}

TEST_F(FetchCommandTest, JsonPrintsTheJob) {
  const auto r = Fetch(Serve(Solution()), dir_.File("out"), {"--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(json::parse(r.out, nullptr, false), JobObject(5, "done", 7));
  EXPECT_TRUE(std::filesystem::exists(dir_.File("out/patches.csv")));
}

TEST_F(FetchCommandTest, AnswerWithoutTheSolutionFails) {
  const auto r = Fetch(OkAnswer({{"job", JobObject(5, "done", 7)}}), dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("missing key 'attachment_bytes'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.File("out")));
}

TEST_F(FetchCommandTest, UndecodableSolutionFails) {
  ControlAnswer answer = OkAnswer({{"job", JobObject(5, "done", 7)}});
  answer.attachment = {1, 2, 3, 4, 5, 6, 7, 8};
  const auto r = Fetch(answer, dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("radfarm: job 5: the job solution from the master: "), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.File("out")));
}

TEST_F(FetchCommandTest, SolutionForAnotherMeshFails) {
  codec::JobSolution short_one = Solution();
  short_one.radiosity.pop_back();
  short_one.unshot.pop_back();
  const auto r = Fetch(Serve(short_one), dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("but the scene meshes into"), std::string::npos) << r.err;
}

// The job's bundle with refinement on, and the solution's values on the scene `scene` names.
codec::JobSolution Refining(const codec::JobSolution& plain, std::vector<uint8_t> scene) {
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(plain.bundle);
  EXPECT_TRUE(bundle.ok());
  bundle->job.refine.enabled = true;
  codec::JobSolution refining = plain;
  refining.bundle = codec::EncodeJobBundle(*bundle);
  refining.scene = std::move(scene);
  return refining;
}

std::vector<uint8_t> MeshBlob(const codec::JobSolution& solution) {
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(solution.bundle);
  EXPECT_TRUE(bundle.ok());
  Result<PatchMesh> mesh = PatchMesh::Build(bundle->scene, bundle->job.mesh, nullptr);
  EXPECT_TRUE(mesh.ok());
  return codec::EncodePatchScene(mesh->patch_scene());
}

// A refining job's values belong to the mesh the solution's scene rebuilds (here one that no step
// split, so the patches are the bundle's), and stats.json counts the patches before and after.
TEST_F(FetchCommandTest, RefinedSolutionsRebuildTheirMesh) {
  const auto r = Fetch(Serve(Refining(Solution(), MeshBlob(Solution()))), dir_.File("out"));
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const json stats = json::parse(ReadFile(dir_.File("out/stats.json")), nullptr, false);
  ASSERT_TRUE(stats.is_object());
  EXPECT_EQ(stats["patches_before_refinement"], double(Solution().radiosity.size()));
  EXPECT_EQ(stats["patches_after_refinement"], double(Solution().radiosity.size()));
}

TEST_F(FetchCommandTest, BadRefinedScenesFail) {
  codec::JobSolution unrefined_job = Solution();
  unrefined_job.scene = MeshBlob(Solution());
  auto r = Fetch(Serve(unrefined_job), dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("holds a refined mesh, but the job does not refine"), std::string::npos)
      << r.err;
  r = Fetch(Serve(Refining(Solution(), {1, 2, 3, 4, 5, 6, 7, 8})), dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("the refined scene in the solution: "), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.File("out")));
}

TEST_F(FetchCommandTest, JobWithoutCheckpointIsInvalidState) {
  const auto r =
      Fetch(testing::ErrorAnswer("invalid_state", "job 5 has no checkpoint yet"), dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_EQ(r.err, "radfarm: job 5 has no checkpoint yet\n");
}

TEST_F(FetchCommandTest, UsesThisMachinesThreadsNotTheJobs) {
  // A job may ask for 65536 threads; more than this machine may start (threads-max), and its
  // cores, not the submitter's, are what fetch has.
  codec::JobSolution solution = Solution();
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(solution.bundle);
  ASSERT_TRUE(bundle.ok()) << bundle.error();
  bundle->job.solver.threads = 65536;
  solution.bundle = codec::EncodeJobBundle(*bundle);
  const auto r = Fetch(Serve(solution), dir_.File("out"));
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_FALSE(ReadFile(dir_.File("out/image.png")).empty());
}

// A job's result is never lost to its outputs: with image.png impossible to write (a directory
// in its place), fetch still writes every other file and names the one it could not.
TEST_F(FetchCommandTest, AnOutputThatCannotBeWrittenIsNamedAndTheOthersAreWritten) {
  const std::string out = dir_.File("out");
  std::filesystem::create_directories(out + "/image.png/in-the-way");
  const auto r = Fetch(Serve(Solution()), out);
  EXPECT_EQ(r.exit_code, kExitFailure) << r.err;
  EXPECT_NE(r.err.find("image.png"), std::string::npos) << r.err;
  for (const char* file : {"patches.csv", "image.exr", "radiosity.ply", "lit.glb", "stats.json"}) {
    EXPECT_FALSE(ReadFile(out + "/" + file).empty()) << file << "\n" << r.err;
  }
}

TEST_F(FetchCommandTest, UnwritableOutputFails) {
  std::ofstream(dir_.File("a-file")) << "in the way";
  const auto r = Fetch(Serve(Solution()), dir_.File("a-file/out"));
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("a-file/out: cannot create the output directory"), std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace radfarm
