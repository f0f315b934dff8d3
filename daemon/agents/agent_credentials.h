// AgentCredentials: the master's in-memory copy of the store's agent_credentials table, loaded at
// start and updated after each enroll or revoke is committed, so the handshake never waits on
// SQLite. It answers ProtocolSession's key_for_agent: an enrolled name proves itself with its own
// key (protocol/agent_key.h), a revoked one is refused, any other name with the farm secret
// (unless shared-secret agents are refused: allow_shared_secret = false).
//
// Loop thread only.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "base/result.h"
#include "protocol/agent_key.h"
#include "protocol/farm_secret.h"
#include "store/job_store.h"

namespace radfarm::daemon {

class AgentCredentials {
 public:
  AgentCredentials(const protocol::FarmSecret& secret,
                   const std::vector<store::AgentCredential>& loaded, bool allow_shared_secret);

  Result<protocol::ExpectedKey> KeyFor(const std::string& name) const;
  // After the store committed an enroll or a revoke.
  void Update(const store::AgentCredential& credential);
  // Every name ever enrolled, revoked ones included, by name (`radfarm agents enrolled`).
  std::vector<store::AgentCredential> List() const;
  // The key of an enrolled credential, for `radfarm agents enroll` to hand out.
  protocol::FarmSecret KeyOf(const store::AgentCredential& credential) const;

 private:
  const protocol::FarmSecret& secret_;
  std::map<std::string, store::AgentCredential> by_name_;
  bool allow_shared_secret_;
};

}  // namespace radfarm::daemon
