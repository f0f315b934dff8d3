#include "daemon/agents/agent_credentials.h"

namespace radfarm::daemon {

AgentCredentials::AgentCredentials(const protocol::FarmSecret& secret,
                                   const std::vector<store::AgentCredential>& loaded,
                                   bool allow_shared_secret)
    : secret_(secret), allow_shared_secret_(allow_shared_secret) {
  for (const store::AgentCredential& c : loaded) by_name_[c.name] = c;
}

Result<protocol::ExpectedKey> AgentCredentials::KeyFor(const std::string& name) const {
  const auto it = by_name_.find(name);
  if (it == by_name_.end()) {
    if (!allow_shared_secret_) {
      return Error{"agent " + name +
                   " is not enrolled and this master refuses the farm secret from agents "
                   "(allow_shared_secret = false); enroll it with `radfarm agents enroll " +
                   name + "`"};
    }
    return protocol::ExpectedKey{secret_, "the farm secret"};
  }
  const store::AgentCredential& c = it->second;
  if (c.revoked) {
    return Error{"the credential of agent " + name + " (generation " +
                 std::to_string(c.generation) + ") is revoked; `radfarm agents enroll " + name +
                 "` issues a new key"};
  }
  return protocol::ExpectedKey{KeyOf(c), "the enrolled key of agent " + name + " (generation " +
                                             std::to_string(c.generation) +
                                             "; a key from an earlier enrolment no longer works)"};
}

void AgentCredentials::Update(const store::AgentCredential& credential) {
  by_name_[credential.name] = credential;
}

std::vector<store::AgentCredential> AgentCredentials::List() const {
  std::vector<store::AgentCredential> list;
  list.reserve(by_name_.size());
  for (const auto& [name, credential] : by_name_) list.push_back(credential);
  return list;
}

protocol::FarmSecret AgentCredentials::KeyOf(const store::AgentCredential& credential) const {
  return protocol::DeriveAgentKey(secret_, credential.name, credential.generation);
}

}  // namespace radfarm::daemon
