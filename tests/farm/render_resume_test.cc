// `radfarm render --db FILE`: an embedded render killed midway continues where it stopped when the
// same command runs again, and ends with the bytes of an uninterrupted render.
#include <signal.h>

#include <filesystem>
#include <fstream>

#include "store/job_store.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

// Opens the render's store once the render has made it (created, in WAL mode: its -wal file
// exists), never creating it: switching a new file to WAL fails with SQLITE_BUSY, without waiting,
// while another connection holds it.
Result<store::JobStore> OpenExisting(const std::string& db) {
  if (!std::filesystem::exists(db + "-wal")) return Error{"not made yet"};
  store::JobStoreOptions options;
  options.database.create = false;
  return store::JobStore::Open(db, options);
}

int64_t Checkpoints(const std::string& db) {
  Result<store::JobStore> s = OpenExisting(db);
  if (!s) return 0;
  Result<int64_t> n = s->CountCheckpoints(1);
  return n ? *n : 0;
}

TEST_F(FarmTest, AKilledEmbeddedRenderContinuesFromItsDatabase) {
  const std::string scene = std::string(RADFARM_SOURCE_DIR) + "/scenes/cornell-box.toml";
  const std::string db = Path("render.db");
  ChildProcess first({RADFARM_CLI_PATH, "render", scene, "--out", Path("first"), "--db", db,
                      "--threads", "1", "-q"},
                     Path("first.log"));
  // Kill it once a couple of rounds are safely in the database.
  ASSERT_TRUE(WaitUntil([&] {
    return Checkpoints(db) >= 2 || first.WaitExit(std::chrono::milliseconds(0)).has_value();
  })) << first.Log();
  ASSERT_TRUE(first.running()) << "the render finished before it could be killed:\n" << first.Log();
  first.Signal(SIGKILL);
  first.WaitExit(std::chrono::seconds(30));

  const CommandResult again =
      RunCommand({RADFARM_CLI_PATH, "render", scene, "--out", Path("again"), "--db", db});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("continuing job 1 after round"), std::string::npos) << again.out;
  EXPECT_TRUE(ReadFile(Path("again") + "/patches.csv") == ReferencePatches("cornell-box.toml"));

  // Done: a third run writes the outputs again from the last checkpoint.
  const CommandResult third =
      RunCommand({RADFARM_CLI_PATH, "render", scene, "--out", Path("third"), "--db", db});
  ASSERT_EQ(third.exit_code, 0) << third.err;
  EXPECT_TRUE(ReadFile(Path("third") + "/patches.csv") == ReferencePatches("cornell-box.toml"));
}

// With adaptive refinement the checkpoints hold the refined mesh: a render killed after a
// refinement point continues on that mesh and ends with the bytes of an uninterrupted render.
TEST_F(FarmTest, AKilledAdaptiveRenderContinuesOnItsRefinedMesh) {
  const std::string scene = std::string(RADFARM_SOURCE_DIR) + "/scenes/cornell-box-adaptive.toml";
  const std::vector<std::string> flags = {"--tolerance", "0.05", "--patch-size", "50"};
  const std::string db = Path("adaptive.db");
  auto refined_checkpoint = [&] {
    Result<store::JobStore> s = OpenExisting(db);
    if (!s) return false;
    Result<std::optional<store::Checkpoint>> c = s->LoadLatestCheckpoint(1);
    // Past the first point after round 0 (its mesh restarts the solution) and a round beyond it.
    return c && *c && (*c)->scene_hash && (*c)->refine_points >= 1 && (*c)->round >= 1;
  };
  std::vector<std::string> args = {RADFARM_CLI_PATH, "render", scene,       "--out", Path("first"),
                                   "--db",           db,       "--threads", "1",     "-q"};
  args.insert(args.end(), flags.begin(), flags.end());
  ChildProcess first(args, Path("first.log"));
  ASSERT_TRUE(WaitUntil([&] {
    return refined_checkpoint() || first.WaitExit(std::chrono::milliseconds(0)).has_value();
  })) << first.Log();
  ASSERT_TRUE(first.running()) << "the render finished before it could be killed:\n" << first.Log();
  first.Signal(SIGKILL);
  first.WaitExit(std::chrono::seconds(30));

  const std::string reference = ReferencePatches("cornell-box-adaptive.toml", flags);
  for (const char* run : {"again", "third"}) {  // the third finds the job done
    std::vector<std::string> again = {RADFARM_CLI_PATH, "render", scene, "--out",
                                      Path(run),        "--db",   db};
    again.insert(again.end(), flags.begin(), flags.end());
    const CommandResult r = RunCommand(again);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("continuing job 1 after round"), std::string::npos) << r.out;
    EXPECT_TRUE(ReadFile(Path(run) + "/patches.csv") == reference) << run;
  }
}

TEST_F(FarmTest, RenderRefusesADatabaseThatIsNotAJobStore) {
  const std::string db = Path("not-a-store.db");
  { std::ofstream(db) << "this is not SQLite"; }
  const CommandResult r = RunCommand({RADFARM_CLI_PATH, "render",
                                      std::string(RADFARM_SOURCE_DIR) + "/scenes/furnace.obj",
                                      "--out", Path("out"), "--db", db, "-q"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--db"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(db), std::string::npos) << r.err;
  EXPECT_EQ(ReadFile(db), "this is not SQLite");  // never overwritten
}

}  // namespace
}  // namespace radfarm::testing
