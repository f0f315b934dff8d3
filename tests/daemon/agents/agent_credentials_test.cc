// AgentCredentials: which key the handshake expects for a name (daemon/agents/agent_credentials.h),
// and the control socket's enroll_agent / revoke_agent requests as parsed.
#include "daemon/agents/agent_credentials.h"

#include <gtest/gtest.h>

#include "daemon/control/control_request_parser.h"

namespace radfarm::daemon {
namespace {

protocol::FarmSecret Farm() {
  return *protocol::FarmSecret::FromBytes(std::vector<uint8_t>(32, 7));
}

store::AgentCredential Credential(const std::string& name, uint64_t generation, bool revoked) {
  store::AgentCredential c;
  c.name = name;
  c.generation = generation;
  c.revoked = revoked;
  return c;
}

TEST(AgentCredentialsTest, AnUnknownNameUsesTheFarmSecret) {
  const protocol::FarmSecret farm = Farm();
  const AgentCredentials credentials(farm, {}, true);
  Result<protocol::ExpectedKey> key = credentials.KeyFor("node-1");
  ASSERT_TRUE(key.ok()) << key.error();
  EXPECT_EQ(key->key.ToHex(), farm.ToHex());
  EXPECT_EQ(key->description, "the farm secret");
}

TEST(AgentCredentialsTest, AnEnrolledNameUsesTheKeyOfItsStoredGeneration) {
  const protocol::FarmSecret farm = Farm();
  AgentCredentials credentials(farm, {Credential("node-1", 1, false)}, true);
  EXPECT_EQ(credentials.KeyFor("node-1")->key.ToHex(),
            protocol::DeriveAgentKey(farm, "node-1", 1).ToHex());
  credentials.Update(Credential("node-1", 2, false));  // enrolled again: a new key
  Result<protocol::ExpectedKey> key = credentials.KeyFor("node-1");
  EXPECT_EQ(key->key.ToHex(), protocol::DeriveAgentKey(farm, "node-1", 2).ToHex());
  EXPECT_NE(key->description.find("generation 2"), std::string::npos) << key->description;
}

TEST(AgentCredentialsTest, ARevokedNameIsRefusedWithTheWayBack) {
  const protocol::FarmSecret farm = Farm();
  AgentCredentials credentials(farm, {Credential("node-1", 1, false)}, true);
  credentials.Update(Credential("node-1", 1, true));
  Result<protocol::ExpectedKey> key = credentials.KeyFor("node-1");
  ASSERT_FALSE(key.ok());
  EXPECT_NE(key.error().find("revoked"), std::string::npos) << key.error();
  EXPECT_NE(key.error().find("radfarm agents enroll node-1"), std::string::npos) << key.error();
  EXPECT_TRUE(credentials.KeyFor("node-2").ok());  // others are not affected
}

TEST(AgentCredentialsTest, WithoutTheSharedSecretOnlyEnrolledAgentsGetIn) {
  const protocol::FarmSecret farm = Farm();
  const AgentCredentials credentials(farm, {Credential("node-1", 1, false)}, false);
  EXPECT_TRUE(credentials.KeyFor("node-1").ok());
  Result<protocol::ExpectedKey> key = credentials.KeyFor("node-2");
  ASSERT_FALSE(key.ok());
  EXPECT_NE(key.error().find("allow_shared_secret = false"), std::string::npos) << key.error();
}

TEST(AgentCredentialsTest, ListsEveryEnrolledNameByNameRevokedOnesIncluded) {
  const protocol::FarmSecret farm = Farm();
  AgentCredentials credentials(farm, {Credential("node-2", 1, false)}, true);
  EXPECT_EQ(credentials.List().size(), 1u);
  credentials.Update(Credential("node-1", 3, true));
  credentials.Update(Credential("node-2", 2, false));
  const std::vector<store::AgentCredential> list = credentials.List();
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].name, "node-1");
  EXPECT_TRUE(list[0].revoked);
  EXPECT_EQ(list[0].generation, 3u);
  EXPECT_EQ(list[1].name, "node-2");
  EXPECT_FALSE(list[1].revoked);
  EXPECT_EQ(list[1].generation, 2u);
}

// (Whether the name is an agent name is checked by ControlRequests: FarmTest.RevokingANameNever...)
TEST(AgentCredentialsTest, ControlRequestsNameOneAgent) {
  uint64_t attachment = 0;
  Result<ControlRequest> enroll = ParseControlRequest(
      nlohmann::json{{"command", "enroll_agent"}, {"name", "node-1"}}, &attachment);
  ASSERT_TRUE(enroll.ok()) << enroll.error();
  EXPECT_EQ(enroll->command, ControlCommand::kEnrollAgent);
  EXPECT_EQ(enroll->name, "node-1");
  Result<ControlRequest> revoke = ParseControlRequest(
      nlohmann::json{{"command", "revoke_agent"}, {"name", "node-1"}}, &attachment);
  ASSERT_TRUE(revoke.ok());
  EXPECT_EQ(revoke->command, ControlCommand::kRevokeAgent);
  Result<ControlRequest> list =
      ParseControlRequest(nlohmann::json{{"command", "enrolled_agents"}}, &attachment);
  ASSERT_TRUE(list.ok()) << list.error();
  EXPECT_EQ(list->command, ControlCommand::kEnrolledAgents);
  for (const nlohmann::json& bad : {nlohmann::json{{"command", "enroll_agent"}},
                                    nlohmann::json{{"command", "enroll_agent"}, {"name", 5}},
                                    nlohmann::json{{"command", "revoke_agent"}}}) {
    Result<ControlRequest> r = ParseControlRequest(bad, &attachment);
    EXPECT_FALSE(r.ok()) << bad.dump();
  }
}

}  // namespace
}  // namespace radfarm::daemon
