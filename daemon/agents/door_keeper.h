// DoorKeeper: the master's quota for connections that have not authenticated yet (issue 20,
// "doors strangers cannot jam"; sshd's MaxStartups is the model). Anyone who reaches the port can
// open connections, so they must not take what belongs to agents:
//
//  - at most max_unauthenticated connections wait in the handshake at once; a new one over the
//    quota makes the oldest waiting one go (not the newcomer: a real agent finishes its handshake
//    in a round trip, while a jammer's connections only wait, so the oldest is the likeliest
//    jammer, and a steady stream of junk cannot keep a newcomer out);
//  - they never count toward --max-agents, which is checked once a peer has authenticated;
//  - each is closed by the handshake deadline, and reads frames of at most
//    protocol::kMaxHandshakeFrameBytes, so the memory they hold is bounded by the quota.
//
// Pure bookkeeping by connection id (ids increase with arrival); AgentConnections closes what it
// says. Loop thread only.
#pragma once

#include <cstdint>
#include <optional>
#include <set>

namespace radfarm::daemon {

struct DoorCounters {
  uint64_t unauthenticated = 0;       // waiting in the handshake now
  uint64_t unauthenticated_peak = 0;  // the most at once since the start
  uint64_t accepted = 0;              // connections accepted
  uint64_t authenticated = 0;         // handshakes passed
  uint64_t evicted = 0;               // closed to make room for a newer one (the quota)
  uint64_t closed_before_auth = 0;    // deadline, malformed or oversized frame, bad proof, EOF
  uint64_t refused_full = 0;          // authenticated with --max-agents agents connected
  // Authenticated while its name had --max-connections-per-agent connections.
  uint64_t refused_per_agent = 0;
};

class DoorKeeper {
 public:
  explicit DoorKeeper(uint32_t max_unauthenticated) : max_(max_unauthenticated) {}

  // Connection `id` was accepted and waits for its handshake. When that passes the quota, the
  // oldest waiting connection is returned: the caller closes it (it no longer counts).
  std::optional<uint64_t> Admit(uint64_t id);
  // `id` passed the handshake: it no longer counts against the quota.
  void Authenticated(uint64_t id);
  // `id` closed without authenticating. False if it had been evicted (counted and logged then).
  bool ClosedBeforeAuth(uint64_t id);
  void RefusedFull() { ++counters_.refused_full; }
  void RefusedPerAgent() { ++counters_.refused_per_agent; }

  uint32_t max_unauthenticated() const { return max_; }
  const DoorCounters& counters() const { return counters_; }

 private:
  const uint32_t max_;
  std::set<uint64_t> waiting_;  // unauthenticated connection ids; the first is the oldest
  DoorCounters counters_;
};

}  // namespace radfarm::daemon
