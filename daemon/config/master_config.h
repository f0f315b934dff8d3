// The master daemon's settings: defaults, overridden by a TOML config file (--config), overridden
// by command-line flags. Every key of the file is a flag of the same name (dashes for
// underscores): see radfarmd --help and packaging/etc/radfarmd.conf.
#pragma once

#include <cstdint>
#include <string>

#include "base/result.h"
#include "store/checkpoint_pacer.h"

namespace radfarm::daemon {

// max_frame_bytes_held at least: one whole frame of protocol::kDefaultMaxFrameBytes (the agents'
// limit; daemon/agents checks that they agree).
inline constexpr uint64_t kMinFrameBytesHeld = uint64_t{16} << 20;

struct MasterConfig {
  std::string listen = "0.0.0.0:7878";  // agents connect here; port 0 picks a free port
  std::string state_dir = "/var/lib/radfarm";
  std::string secret_file = "/etc/radfarm/secret";
  std::string control;  // the control socket; empty: STATE/control.sock
  uint32_t heartbeat_ms = 1000;
  uint32_t agent_timeout_ms = 5000;      // silent this long: the agent's leases go back
  uint32_t handshake_timeout_ms = 5000;  // unauthenticated this long: the connection is closed
  // A control client must send each whole request (attachment included) within this.
  uint32_t control_timeout_ms = 60000;
  std::string log_level = "info";
  uint32_t checkpoint_keep = 3;   // full checkpoints kept per job
  double checkpoint_seconds = 0;  // 0: checkpoint every round; else at most this often
  // A job's checkpoints, from queued to committed, take at most this share of its time: the next
  // waits until it fits (0: no such wait; store/checkpoint_pacer.h): a big job's checkpoint takes
  // seconds.
  double checkpoint_time_share = store::kDefaultCheckpointTimeShare;
  uint32_t max_running_jobs = 4;  // jobs solved at once; more wait queued
  double lease_seconds = 0.25;    // the time one batch should take on its agent
  // Rounds of at most this many rays are computed by the master itself (0: never): the last
  // rounds of a solve are a few rays per patch, which cost agents a round trip per batch.
  uint64_t local_round_rays = 262144;
  // The final gather's first rays, at most this many, go to agents idle between and at the ends
  // of the shooting rounds (daemon/jobs/gather_ahead.h); their results wait on the master until the
  // gather round: a few bytes a ray, a fixed cost whatever the scene's size (docs/MEMORY.md).
  // 0: off.
  uint64_t gather_ahead_rays = uint64_t{1} << 20;
  // Keep each accepted batch result in the store until its round's checkpoint, so a restarted
  // master leases only the batches it had not received (daemon/jobs/result_journal.h). Off: a
  // restart computes the whole round again.
  bool keep_round_results = true;
  // ... but only the results accepted once a round has run this long: a short round is cheaper to
  // compute again than to write (keeping every result of a small job's short rounds costs a good
  // share of its time), and a kill loses at most this much of a round's work.
  double keep_results_after_seconds = 5;
  // A job that meets a store fault (disk full, I/O error) is held and tried again this often.
  uint32_t hold_retry_ms = 10000;
  // The job store's size at most (0: no limit but the disk's). Reaching it is like a full disk:
  // running jobs are held until there is room.
  uint64_t max_store_bytes = 0;
  // An agent whose results fail validation 3 times for a job (authenticated, so not the wire's
  // fault) gets no more of that job's work for this long (job_blocklist.h).
  uint32_t blocklist_seconds = 600;
  // Exact validation (daemon/jobs/batch_verifier.h): this fraction of each agent's accepted
  // batches, and at least one per agent and round it contributed to, is computed again by the
  // master and compared bit for bit; a mismatch blocklists the agent and computes its results
  // again. 0: off.
  double verify_fraction = 0.02;
  uint32_t max_agents = 4096;  // authenticated agents beyond this are refused
  // Connections still in the handshake at once; a newer one makes the oldest go (door_keeper.h).
  uint32_t max_unauthenticated = 64;
  // Authenticated connections at once under one agent name (an enrolled name's key is its own):
  // more are refused after their handshake, so one credential cannot take every --max-agents
  // place. 2 lets an agent whose old connection the master has not yet seen die come back.
  uint32_t max_connections_per_agent = 2;
  // Bytes the master holds at once in frames still arriving, over every agent connection
  // (loop/frame_budget.h): a frame that would pass it closes the connection holding the most, so
  // peers trickling big frames cannot hold the master's memory nor starve small frames. At least
  // one whole frame of the largest size.
  uint64_t max_frame_bytes_held = uint64_t{256} << 20;
  // Whether an agent that is not enrolled (`radfarm agents enroll`) may prove itself with the farm
  // secret. false: only enrolled agents, each with its own key, which can be revoked alone.
  bool allow_shared_secret = true;
  // The web console (status page, /metrics): HOST:PORT, empty = off. A host other than loopback
  // needs http_token_file (the token that reading and acting then need).
  std::string http;
  std::string http_token_file;

  std::string ControlPath() const;
  std::string DatabasePath() const;
  std::string ListenAddrPath() const;
  std::string HttpAddrPath() const;  // STATE/http.addr: the web console's bound HOST:PORT
};

// Reads `path` over `config`: unknown keys, wrong types and out-of-range values are errors naming
// the file, line and key.
Status ReadMasterConfigFile(const std::string& path, MasterConfig* config);

// The checks no single key can make (called after flags are applied).
Status CheckMasterConfig(const MasterConfig& config);

// Whether a result accepted `round_seconds` into its round is kept for a restart.
inline bool KeepsRoundResult(const MasterConfig& config, double round_seconds) {
  return config.keep_round_results && round_seconds >= config.keep_results_after_seconds;
}

}  // namespace radfarm::daemon
