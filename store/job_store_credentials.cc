// JobStore: per-agent credentials (the rest is in job_store.cc).
#include "base/result.h"
#include "store/job_store.h"

namespace radfarm::store {
namespace {

constexpr char kSelectCredential[] =
    "SELECT name, generation, revoked, enrolled_at_ms, revoked_at_ms FROM agent_credentials";

AgentCredential CredentialOf(Statement& stmt) {
  AgentCredential c;
  c.name = stmt.Text(0);
  c.generation = static_cast<uint64_t>(stmt.Int(1));
  c.revoked = stmt.Int(2) != 0;
  c.enrolled_at_ms = stmt.Int(3);
  if (!stmt.IsNull(4)) c.revoked_at_ms = stmt.Int(4);
  return c;
}

Result<std::optional<AgentCredential>> ReadCredential(Database& db, const std::string& name) {
  Result<Statement> stmt = db.Prepare(std::string(kSelectCredential) + " WHERE name = ?1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, name);
  Result<bool> row = stmt->Step();
  RADFARM_RETURN_IF_ERROR(row);
  if (!*row) return std::optional<AgentCredential>();
  return std::optional<AgentCredential>(CredentialOf(*stmt));
}

}  // namespace

Result<AgentCredential> JobStore::EnrollAgent(const std::string& name) {
  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  Result<Statement> stmt = db_.Prepare(
      "INSERT INTO agent_credentials (name, generation, revoked, enrolled_at_ms)"
      " VALUES (?1, 1, 0, ?2)"
      " ON CONFLICT (name) DO UPDATE SET generation = generation + 1, revoked = 0,"
      " enrolled_at_ms = excluded.enrolled_at_ms, revoked_at_ms = NULL");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, name).Bind(2, now_ms_());
  RADFARM_RETURN_IF_ERROR(stmt->Run());
  Result<std::optional<AgentCredential>> enrolled = ReadCredential(db_, name);
  RADFARM_RETURN_IF_ERROR(enrolled);
  RADFARM_RETURN_IF_ERROR(transaction->Commit());
  return **enrolled;
}

Result<std::optional<AgentCredential>> JobStore::RevokeAgent(const std::string& name) {
  Result<Transaction> transaction = Transaction::Begin(db_);
  RADFARM_RETURN_IF_ERROR(transaction);
  Result<Statement> stmt = db_.Prepare(
      "UPDATE agent_credentials SET revoked = 1, revoked_at_ms = coalesce(revoked_at_ms, ?2)"
      " WHERE name = ?1");
  RADFARM_RETURN_IF_ERROR(stmt);
  stmt->Bind(1, name).Bind(2, now_ms_());
  RADFARM_RETURN_IF_ERROR(stmt->Run());
  Result<std::optional<AgentCredential>> revoked = ReadCredential(db_, name);
  RADFARM_RETURN_IF_ERROR(revoked);
  RADFARM_RETURN_IF_ERROR(transaction->Commit());
  return revoked;
}

Result<std::vector<AgentCredential>> JobStore::ListAgentCredentials() {
  Result<Statement> stmt = db_.Prepare(std::string(kSelectCredential) + " ORDER BY name");
  RADFARM_RETURN_IF_ERROR(stmt);
  std::vector<AgentCredential> credentials;
  while (true) {
    Result<bool> row = stmt->Step();
    RADFARM_RETURN_IF_ERROR(row);
    if (!*row) return credentials;
    credentials.push_back(CredentialOf(*stmt));
  }
}

}  // namespace radfarm::store
