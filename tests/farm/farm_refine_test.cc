// Adaptive refinement in farm mode: the master refines at the rounds `radfarm render` refines at,
// ships each refined scene to the agents, keeps the refined mesh in its checkpoints, and a job ends
// with the bytes of `radfarm render` however many agents work on it, whether they scored its
// refinement steps and whether the master was killed after a refinement point.
#include <signal.h>

#include <filesystem>

#include "cli/farm_command.h"
#include "codec/job_bundle.h"
#include "input/input_scene.h"
#include "job/job.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

const std::string kAdaptive = "cornell-box-adaptive.toml";
// A tolerance below the refinement point (0.6 unshot): the job refines before round 0 and
// restarts on the mesh refined after its first round (kRefinePoints). The patch size
// is pinned to keep the job short whatever the shipped job file says.
const std::vector<std::string> kFlags = {"--tolerance", "0.05", "--patch-size", "50"};

// The number after "key": in a flat JSON object (stats.json).
double JsonNumber(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return -1;
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

// stats.json and image.exr of `radfarm render` of the adaptive job (ReferencePatches renders the
// patches).
struct RenderFiles {
  std::string stats, image;
};
const RenderFiles& ReferenceFiles() {
  static const RenderFiles files = [] {
    TempDir out;
    std::vector<std::string> args = {
        RADFARM_CLI_PATH, "render",   std::string(RADFARM_SOURCE_DIR "/scenes/") + kAdaptive,
        "--out",          out.path(), "-q"};
    args.insert(args.end(), kFlags.begin(), kFlags.end());
    const CommandResult r = RunCommand(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return RenderFiles{ReadFile(out.File("stats.json")), ReadFile(out.File("image.exr"))};
  }();
  return files;
}

class FarmRefineTest : public FarmTest {
 protected:
  // `radfarm fetch` of the job gives the patches and patch counts of `radfarm render`.
  void ExpectLikeRender(int64_t id);
};

void FarmRefineTest::ExpectLikeRender(int64_t id) {
  const std::string patches = FetchPatches(id);
  ASSERT_FALSE(patches.empty());
  EXPECT_TRUE(patches == ReferencePatches(kAdaptive, kFlags)) << "farm and render differ";
  const std::string stats = ReadFile(Path("fetch-" + std::to_string(id)) + "/stats.json");
  const std::string& reference = ReferenceFiles().stats;
  // The image too: its vertices' direct light is recomputed from the refined mesh by fetch.
  const std::string image = ReadFile(Path("fetch-" + std::to_string(id)) + "/image.exr");
  EXPECT_FALSE(image.empty());
  EXPECT_TRUE(image == ReferenceFiles().image) << "farm and render images differ";
  for (const char* key : {"patches_before_refinement", "patches_after_refinement", "patches",
                          "rays", "rounds", "unshot_fraction"}) {
    EXPECT_EQ(JsonNumber(stats, key), JsonNumber(reference, key)) << key << "\n" << stats;
  }
  EXPECT_GT(JsonNumber(stats, "patches_after_refinement"),
            JsonNumber(stats, "patches_before_refinement"));
}

TEST_F(FarmRefineTest, ThreeAgentsRenderAnAdaptiveJobLikeRadfarmRender) {
  StartMaster();
  for (const char* name : {"r1", "r2", "r3"}) StartAgent(name);
  const int64_t id = Submit(kAdaptive, kFlags);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_EQ(Status(id)["stop_reason"], "converged");
  ExpectLikeRender(id);
  // The restart point after round 0 split elements: a new scene the agents fetched.
  const std::string log = MasterLog();
  EXPECT_GE(CountLines(log, "refined after round 1:"), 1u) << log;
  EXPECT_GE(CountLines(log, "fetches the scene of job"), 2u) << log;
  // The step after round 0 is made while the agents trace: they scored its elements, to the bits
  // render scores them to.
  EXPECT_GE(CountLines(log, "refinement's light scores:"), 1u) << log;
}

TEST_F(FarmRefineTest, TheMasterKilledAfterARefinementPointResumesTheAdaptiveJobIdentically) {
  StartMaster();
  const std::string listen =
      "127.0.0.1:" + master_address().substr(master_address().rfind(':') + 1);
  StartAgent("k1");
  StartAgent("k2");
  const int64_t id = Submit(kAdaptive, kFlags);
  // The first refinement point is passed after round 0; once a later round is in (and with it a
  // checkpoint of the refined mesh: the master checkpoints every round), kill the master.
  ASSERT_TRUE(WaitUntil(
      [&] {
        return CountLines(MasterLog(), "refined after round") >= 1 && JobRound(Status(id)) >= 2;
      },
      kJobTimeout))
      << MasterLog();
  ASSERT_NE(Status(id)["state"], "done") << "the job ended before the master could be killed";
  master().Signal(SIGKILL);
  ASSERT_TRUE(master().WaitExit(std::chrono::seconds(30)).has_value());
  StartMaster({"--listen", listen});
  ASSERT_TRUE(WaitForState(id, "done"));
  const std::string log = MasterLog();
  EXPECT_GE(CountLines(log, "resuming after round"), 1u) << log;
  ExpectLikeRender(id);
}

// `radfarm submit` checks the refine settings against the mesh before sending; the master checks
// them again, for a bundle that did not come through it.
TEST_F(FarmRefineTest, TheMasterRefusesRefineSettingsThatDoNotFitTheMesh) {
  StartMaster();
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/" + kAdaptive);
  ASSERT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  job->refine.min_element_size = 1e-9;  // decodes (finite, >= 0); below the welding distance
  const std::vector<uint8_t> bundle = codec::EncodeJobBundle({*job, *scene});
  Outcome<ControlReply> reply =
      AskMaster(control(), {{"command", "submit"}, {"name", "tiny"}, {"priority", 0}}, bundle);
  ASSERT_FALSE(reply.ok());
  EXPECT_NE(reply.failure().message.find("mesh.min_element_size"), std::string::npos)
      << reply.failure().message;
  const CommandResult list = Cli({"list", "--json"});
  ASSERT_EQ(list.exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(list.out).size(), 0u);
}

}  // namespace
}  // namespace radfarm::testing
