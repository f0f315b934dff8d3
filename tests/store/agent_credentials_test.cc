// agent_credentials: enrolling, re-enrolling (a new generation) and revoking agents, and their
// survival across a reopen (the master loads them at start).
#include <gtest/gtest.h>

#include "store/job_store.h"
#include "tests/store/temp_dir.h"

namespace radfarm::store {
namespace {

class AgentCredentialsTest : public ::testing::Test {
 protected:
  void SetUp() override { Open(); }
  void Open() {
    store_.reset();
    JobStoreOptions options;
    options.now_ms = clock_.Function();
    Result<JobStore> store = JobStore::Open(dir_.File("jobs.db"), options);
    ASSERT_TRUE(store.ok()) << store.error();
    store_.emplace(std::move(*store));
  }

  TempDir dir_;
  FakeClock clock_;
  std::optional<JobStore> store_;
};

TEST_F(AgentCredentialsTest, EnrollStartsAtGenerationOne) {
  Result<AgentCredential> c = store_->EnrollAgent("node-1");
  ASSERT_TRUE(c.ok()) << c.error();
  EXPECT_EQ(c->name, "node-1");
  EXPECT_EQ(c->generation, 1u);
  EXPECT_FALSE(c->revoked);
  EXPECT_EQ(c->enrolled_at_ms, *clock_.now);
  EXPECT_FALSE(c->revoked_at_ms);
}

TEST_F(AgentCredentialsTest, RevokeThenEnrollAgainGivesTheNextGeneration) {
  ASSERT_TRUE(store_->EnrollAgent("node-1").ok());
  clock_.Advance(1000);
  Result<std::optional<AgentCredential>> revoked = store_->RevokeAgent("node-1");
  ASSERT_TRUE(revoked.ok() && revoked->has_value());
  EXPECT_TRUE((*revoked)->revoked);
  EXPECT_EQ((*revoked)->generation, 1u);
  EXPECT_EQ((*revoked)->revoked_at_ms, *clock_.now);
  clock_.Advance(1000);
  Result<AgentCredential> again = store_->EnrollAgent("node-1");
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->generation, 2u);
  EXPECT_FALSE(again->revoked);
  EXPECT_FALSE(again->revoked_at_ms);
  // Enrolling an enrolled name rotates its key too.
  EXPECT_EQ(store_->EnrollAgent("node-1")->generation, 3u);
}

TEST_F(AgentCredentialsTest, RevokingANameNeverEnrolledFindsNothing) {
  Result<std::optional<AgentCredential>> revoked = store_->RevokeAgent("stranger");
  ASSERT_TRUE(revoked.ok());
  EXPECT_FALSE(revoked->has_value());
  EXPECT_TRUE(store_->ListAgentCredentials()->empty());
}

TEST_F(AgentCredentialsTest, CredentialsSurviveAReopen) {
  ASSERT_TRUE(store_->EnrollAgent("b").ok());
  ASSERT_TRUE(store_->EnrollAgent("a").ok());
  ASSERT_TRUE(store_->RevokeAgent("b").ok());
  Open();
  Result<std::vector<AgentCredential>> all = store_->ListAgentCredentials();
  ASSERT_TRUE(all.ok()) << all.error();
  ASSERT_EQ(all->size(), 2u);
  EXPECT_EQ((*all)[0].name, "a");
  EXPECT_FALSE((*all)[0].revoked);
  EXPECT_EQ((*all)[1].name, "b");
  EXPECT_TRUE((*all)[1].revoked);
}

}  // namespace
}  // namespace radfarm::store
