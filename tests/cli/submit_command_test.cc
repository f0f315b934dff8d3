// `radfarm submit` against a fake master: the request and its job bundle, the id on stdout, and
// bad scenes refused locally, with render's messages, before any connection.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/exit_codes.h"
#include "cli/job_inputs.h"
#include "codec/job_bundle.h"
#include "core/thread_pool.h"
#include "tests/cli/control_fixtures.h"
#include "tests/cli/fake_control_server.h"

namespace radfarm {
namespace {

using nlohmann::json;
using testing::ControlRequest;
using testing::FakeControlServer;
using testing::JobObject;
using testing::OkAnswer;
using testing::RunCommand;
using testing::RunFarm;
using testing::TempDir;
using testing::UnixListener;

const std::string kCornell = RADFARM_SOURCE_DIR "/scenes/cornell-box.toml";
const std::string kBadData = RADFARM_SOURCE_DIR "/tests/input/data/";

FakeControlServer::Handler AnswerJob(int64_t id) {
  return [id](const ControlRequest&) { return OkAnswer({{"job", JobObject(id, "queued")}}); };
}

TEST(SubmitCommandTest, SendsTheBundleWithOverridesAndPrintsTheId) {
  FakeControlServer server(AnswerJob(42));
  const std::vector<std::string> overrides = {"--seed",    "9",      "--tolerance",  "0.05",
                                              "--sampler", "random", "--patch-size", "50",
                                              "--rays",    "123456", "--seconds",    "60"};
  std::vector<std::string> args = {"submit", kCornell, "--name", "box", "--priority", "-3"};
  args.insert(args.end(), overrides.begin(), overrides.end());
  args.insert(args.end(), {"--lightmap-size", "256"});
  const auto r = RunFarm(server.socket_path(), args);
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.out, "42\n");

  const std::vector<ControlRequest> requests = server.requests();
  ASSERT_EQ(requests.size(), 1u);
  const ControlRequest& request = requests[0];
  EXPECT_EQ(request.body, json({{"command", "submit"},
                                {"name", "box"},
                                {"priority", -3},
                                {"attachment_bytes", request.attachment.size()}}));
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(request.attachment);
  ASSERT_TRUE(bundle.ok()) << bundle.error();
  const SolverSettings& s = bundle->job.solver;
  EXPECT_EQ(s.seed, 9u);
  EXPECT_EQ(s.tolerance, 0.05);
  EXPECT_EQ(s.sampler, SamplerKind::kRandom);
  EXPECT_EQ(s.max_rays, 123456u);
  EXPECT_EQ(s.max_seconds, 60.0);
  EXPECT_EQ(bundle->job.mesh.patch_size, 50.0);
  EXPECT_EQ(bundle->job.lightmap_size, 256u);  // `radfarm fetch` bakes at the submitted size

  // Exactly the bundle of the job as `render` would load it with the same options.
  JobOverrides same;
  same.seed = 9;
  same.tolerance = 0.05;
  same.sampler = "random";
  same.patch_size = 50;
  same.rays = 123456;
  same.seconds = 60;
  same.lightmap_size = 256;
  std::vector<std::string> warnings;
  Result<LoadedJob> local = LoadJobForSolve(kCornell, same, &warnings);
  ASSERT_TRUE(local.ok()) << local.error();
  EXPECT_EQ(request.attachment, codec::EncodeJobBundle({local->job, local->scene}));
}

TEST(SubmitCommandTest, DefaultsAreAnEmptyNameAndPriorityZero) {
  FakeControlServer server(AnswerJob(1));
  const auto r = RunFarm(server.socket_path(), {"submit", kCornell});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ASSERT_EQ(server.requests().size(), 1u);
  const json body = server.requests()[0].body;
  EXPECT_EQ(body["name"], "");
  EXPECT_EQ(body["priority"], 0);
}

TEST(SubmitCommandTest, JsonPrintsTheNewJob) {
  FakeControlServer server(AnswerJob(5));
  const auto r = RunFarm(server.socket_path(), {"submit", kCornell, "--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(json::parse(r.out, nullptr, false), JobObject(5, "queued"));
}

TEST(SubmitCommandTest, MastersRefusalExits2) {
  FakeControlServer server([](const ControlRequest&) {
    return testing::ErrorAnswer("bad_request", "job bundle: face 3: index out of range");
  });
  const auto r = RunFarm(server.socket_path(), {"submit", kCornell});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_EQ(r.err, "radfarm: job bundle: face 3: index out of range\n");
  EXPECT_EQ(r.out, "");
}

// Each bad scene fails as `radfarm render` fails on it, word for word, and never connects.
TEST(SubmitCommandTest, BadScenesFailLocallyLikeRenderWithoutConnecting) {
  TempDir dir;
  UnixListener listener(dir);
  {
    std::ofstream(dir.File("flat.mtl")) << "newmtl light\nKd 0.5 0.5 0.5\nKe 1 1 1\n";
    std::ofstream(dir.File("flat.obj")) << "mtllib flat.mtl\nv 0 0 0\nv 1 0 0\nv 2 0 0\n"
                                           "usemtl light\nf 1 2 3\n";
  }
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{kBadData + "index_out_of_range.obj"}, "index_out_of_range.obj:11: vertex index 9"},
      {{kBadData + "kd_too_high.obj"}, "kd_too_high.mtl:5: material 'mirror'"},
      {{kBadData + "jobs/unknown_key.toml"}, "unknown_key.toml:"},
      {{kBadData + "does_not_exist.obj"}, "does_not_exist.obj: cannot open"},
      {{dir.File("flat.obj")}, "flat.obj: no faces left to mesh"},  // a meshing error
      {{kCornell, "--patch-size", "1e-5"}, "would make over 8388608 patches"},
  };
  for (const auto& [scene_args, message] : cases) {
    std::vector<std::string> submit = {"submit"};
    submit.insert(submit.end(), scene_args.begin(), scene_args.end());
    const auto r = RunFarm(listener.path(), submit);
    EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
    EXPECT_NE(r.err.find("radfarm: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << message << " in " << r.err;
    EXPECT_EQ(r.out, "");

    std::vector<std::string> render = {RADFARM_CLI_PATH, "render", "--out", dir.File("out")};
    render.insert(render.end(), scene_args.begin(), scene_args.end());
    const auto rendered = RunCommand(render);
    EXPECT_EQ(rendered.exit_code, kExitBadInput);
    EXPECT_EQ(r.err, rendered.err) << "submit and render disagree";
  }
  EXPECT_FALSE(listener.HasPendingConnection()) << "submit connected despite a bad scene";
}

// Hostile scenes, threads: a job file saying threads = 65536 made `submit` mesh on that many
// threads, and abort where the system refused one. It meshes on this machine's cores at most:
// with address space for a few hundred thread stacks, not 65536, it still submits.
TEST(SubmitCommandTest, AJobFileAskingFor65536ThreadsMeshesOnThisMachinesCores) {
  TempDir dir;
  for (const char* file : {"cornell-box.obj", "cornell-box.mtl"}) {
    std::filesystem::copy_file(RADFARM_SOURCE_DIR "/scenes/" + std::string(file), dir.File(file));
  }
  std::ofstream(dir.File("greedy.toml"))
      << "scene = \"cornell-box.obj\"\n[mesh]\npatch_size = 25.0\n[solver]\nthreads = 65536\n";
  FakeControlServer server(AnswerJob(7));
  const auto r =
      RunCommand({"/bin/sh", "-c", "ulimit -v 2097152 && exec \"$@\"", "sh", RADFARM_CLI_PATH,
                  "--control", server.socket_path(), "submit", dir.File("greedy.toml")});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.out, "7\n");
  ASSERT_EQ(server.requests().size(), 1u);
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(server.requests()[0].attachment);
  ASSERT_TRUE(bundle.ok()) << bundle.error();
  EXPECT_LE(bundle->job.solver.threads, MachineThreads());
}

TEST(SubmitCommandTest, BadOverridesAreUsageErrors) {
  TempDir dir;
  UnixListener listener(dir);
  for (const std::vector<std::string>& extra :
       std::vector<std::vector<std::string>>{{"--sampler", "fancy"},
                                             {"--tolerance", "2"},
                                             {"--rays", "-1"},
                                             {"--priority", "x"},
                                             {"--lightmap-size", "4"}}) {
    std::vector<std::string> args = {"submit", kCornell};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = RunFarm(listener.path(), args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << extra[0] << ": " << r.err;
  }
  EXPECT_FALSE(listener.HasPendingConnection());
}

}  // namespace
}  // namespace radfarm
