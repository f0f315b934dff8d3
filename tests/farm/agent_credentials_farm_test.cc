// Per-agent credentials end to end: `radfarm agents enroll` gives an agent its own key, with which
// it works; `radfarm agents revoke` closes its connection at once and refuses it from then on,
// while an agent on the farm secret keeps working and the job still ends with render's bytes;
// enrolling the name again issues a new key that works, and the old one stays refused.
#include <fstream>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

// The entry for `name` in `radfarm agents enrolled --json`'s output (null when it is not listed).
nlohmann::json EnrolledEntry(const CommandResult& listed, const std::string& name) {
  EXPECT_EQ(listed.exit_code, 0) << listed.err;
  const nlohmann::json list = nlohmann::json::parse(listed.out, nullptr, false);
  if (!list.is_array()) return nullptr;
  for (const nlohmann::json& entry : list) {
    if (entry.value("name", "") == name) return entry;
  }
  return nullptr;
}

TEST_F(FarmTest, AnEnrolledAgentWorksWithItsKeyAndARevokeCutsItOffAtOnce) {
  StartMaster();
  const std::string key_file = Path("keyed.key");
  const CommandResult enrolled = Cli({"agents", "enroll", "keyed", "--out", key_file});
  ASSERT_EQ(enrolled.exit_code, 0) << enrolled.err << MasterLog();
  EXPECT_NE(enrolled.out.find("generation 1"), std::string::npos) << enrolled.out;

  // Alone on the farm with its own key, the agent runs a whole job.
  ChildProcess& keyed = StartAgent("keyed", {}, key_file);
  const int64_t first = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(first, "done")) << keyed.Log();
  EXPECT_TRUE(FetchPatches(first) == ReferencePatches("cornell-box.toml", kShortJob));
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "keyed@", " connected ("), 1u) << MasterLog();
  const nlohmann::json listed = EnrolledEntry(Cli({"agents", "enrolled", "--json"}), "keyed");
  EXPECT_EQ(listed.value("generation", 0), 1) << listed.dump();
  EXPECT_EQ(listed.value("revoked", true), false) << listed.dump();
  EXPECT_EQ(listed.value("connected", 0), 1) << listed.dump();
  const CommandResult table = Cli({"agents", "enrolled"});
  EXPECT_NE(table.out.find("keyed"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("enrolled"), std::string::npos) << table.out;

  // A shared-secret agent joins; the enrolled one is revoked while connected.
  ChildProcess& shared = StartAgent("shared");
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "shared") >= 0; })) << MasterLog();
  const int64_t second = Submit("cornell-box.toml", kShortJob);
  const CommandResult revoked = Cli({"agents", "revoke", "keyed", "--json"});
  ASSERT_EQ(revoked.exit_code, 0) << revoked.err << MasterLog();
  EXPECT_EQ(nlohmann::json::parse(revoked.out).value("closed", -1), 1) << revoked.out;
  // Closed at once (the close completes on the master's next loop turn): the master said why, and
  // so does the agent.
  EXPECT_TRUE(WaitUntil([&] {
    return CountLinesWithBoth(MasterLog(), "keyed@", "was revoked") >= 1;
  })) << MasterLog();
  ASSERT_TRUE(WaitUntil([&] { return keyed.Log().find("revoked: ") != std::string::npos; }))
      << keyed.Log();
  EXPECT_LT(AgentLeases(Agents(), "keyed"), 0) << Agents().dump();
  const nlohmann::json revoked_entry =
      EnrolledEntry(Cli({"agents", "enrolled", "--json"}), "keyed");
  EXPECT_EQ(revoked_entry.value("revoked", false), true) << revoked_entry.dump();
  EXPECT_EQ(revoked_entry.value("connected", 1), 0) << revoked_entry.dump();
  EXPECT_TRUE(revoked_entry["revoked_at_ms"].is_number_integer()) << revoked_entry.dump();
  EXPECT_TRUE(EnrolledEntry(Cli({"agents", "enrolled", "--json"}), "shared")
                  .is_null());  // on the farm secret: not listed
  // It tries again and is refused at its Hello, every time.
  ASSERT_TRUE(WaitUntil([&] {
    return CountLinesWithBoth(keyed.Log(), "authentication with", "is revoked") >= 2;
  })) << keyed.Log();
  EXPECT_GE(CountLines(MasterLog(), "the credential of agent keyed (generation 1) is revoked"), 1u)
      << MasterLog();

  ASSERT_TRUE(WaitForState(second, "done")) << shared.Log();
  EXPECT_TRUE(FetchPatches(second) == ReferencePatches("cornell-box.toml", kShortJob));
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "keyed@", " connected ("), 1u) << MasterLog();
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "shared@", "disconnected"), 0u) << MasterLog();

  // Enrolled again: a new key (generation 2) gets in; the revoked one still does not.
  const std::string new_key_file = Path("keyed-2.key");
  const CommandResult again = Cli({"agents", "enroll", "keyed", "--out", new_key_file});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("generation 2"), std::string::npos) << again.out;
  ASSERT_TRUE(WaitUntil([&] {
    return CountLines(MasterLog(), "the enrolled key of agent keyed (generation 2") >= 1;
  })) << MasterLog();
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "keyed@", " connected ("), 1u) << MasterLog();
  keyed.Kill();
  StartAgent("keyed", {}, new_key_file);
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "keyed") >= 0; })) << MasterLog();
}

TEST_F(FarmTest, RevokingANameNeverEnrolledIsNotFoundAndEnrollNeedsAValidName) {
  StartMaster();
  const CommandResult unknown = Cli({"agents", "revoke", "stranger"});
  EXPECT_EQ(unknown.exit_code, 2) << unknown.err;
  EXPECT_NE(unknown.err.find("agent stranger is not enrolled"), std::string::npos) << unknown.err;
  const CommandResult bad = Cli({"agents", "enroll", "two words"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("must be an agent name"), std::string::npos) << bad.err;
}

TEST_F(FarmTest, WithoutTheSharedSecretOnlyEnrolledAgentsGetIn) {
  const std::string config = Path("master.toml");
  { std::ofstream(config) << "allow_shared_secret = false\n"; }
  StartMaster({"--config", config});
  ASSERT_EQ(Cli({"agents", "enroll", "keyed", "--out", Path("keyed.key")}).exit_code, 0);
  ChildProcess& shared = StartAgent("shared");
  StartAgent("keyed", {}, Path("keyed.key"));
  ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "keyed") >= 0; })) << MasterLog();
  ASSERT_TRUE(WaitUntil([&] {
    return shared.Log().find("allow_shared_secret = false") != std::string::npos;
  })) << shared.Log();
  EXPECT_LT(AgentLeases(Agents(), "shared"), 0);
}

}  // namespace
}  // namespace radfarm::testing
