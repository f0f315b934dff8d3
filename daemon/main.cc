// radfarmd: the master daemon. Parses its settings (flags over --config over defaults), reads the
// farm secret, starts the Master on one event loop and runs it until SIGTERM or SIGINT.
// Exit codes: 0 after a clean stop, 1 when it cannot start (store, listener) or fails, 2 for bad
// usage, configuration or secret.
#include <signal.h>
#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>

#include "base/result.h"
#include "base/text_file.h"
#include "daemon/config/master_config.h"
#include "daemon/detach.h"
#include "daemon/master.h"
#include "loop/event_loop.h"
#include "loop/log.h"

namespace radfarm::daemon {
namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

struct Flags {
  std::optional<std::string> config, listen, state_dir, secret_file, control, log_level, http,
      http_token_file;
  std::optional<uint32_t> heartbeat_ms, agent_timeout_ms, handshake_timeout_ms, control_timeout_ms,
      hold_retry_ms, checkpoint_keep, max_running_jobs, max_agents, max_unauthenticated,
      max_connections_per_agent, blocklist_seconds;
  std::optional<double> checkpoint_seconds, checkpoint_time_share, lease_seconds,
      keep_results_after_seconds, verify_fraction;
  std::optional<uint64_t> local_round_rays, gather_ahead_rays, max_store_bytes,
      max_frame_bytes_held;
  std::optional<bool> keep_round_results;
  bool detach = false;
};

void AddFlags(CLI::App& app, Flags* f) {
  app.add_option("--config", f->config, "TOML file with any of the settings below (flags win)");
  app.add_option("--listen", f->listen,
                 "HOST:PORT agents connect to; port 0 picks a free one, written to "
                 "STATE/listen.addr (default 0.0.0.0:7878)");
  app.add_option("--state-dir", f->state_dir,
                 "Job store, control socket and listen.addr (default /var/lib/radfarm)");
  app.add_option("--secret-file", f->secret_file,
                 "The farm secret, hex (default /etc/radfarm/secret; make one with "
                 "`radfarm secret new FILE`)");
  app.add_option("--control", f->control, "Control socket path (default STATE/control.sock)");
  app.add_option("--log-level", f->log_level, "debug, info, warning or error (default info)");
  app.add_option("--heartbeat-ms", f->heartbeat_ms, "Heartbeat interval (default 1000)")
      ->check(CLI::Range(10u, 86400000u));
  app.add_option("--agent-timeout-ms", f->agent_timeout_ms,
                 "An agent silent this long loses its leases (default 5000)")
      ->check(CLI::Range(100u, 86400000u));
  app.add_option("--handshake-timeout-ms", f->handshake_timeout_ms,
                 "Close connections not authenticated within this (default 5000)")
      ->check(CLI::Range(100u, 86400000u));
  app.add_option("--control-timeout-ms", f->control_timeout_ms,
                 "A control client must send each whole request, attachment included, within "
                 "this; idle clients are closed (default 60000)")
      ->check(CLI::Range(100u, 86400000u));
  app.add_option("--blocklist-seconds", f->blocklist_seconds,
                 "An agent whose results fail validation 3 times for a job gets none of that "
                 "job's work for this long (default 600)")
      ->check(CLI::Range(1u, 604800u));
  app.add_option("--verify-fraction", f->verify_fraction,
                 "This fraction of each agent's batches (and at least one per agent and round) "
                 "is computed again by the master and compared bit for bit; a mismatch "
                 "blocklists the agent and its results are computed again; 0 = off (default "
                 "0.02)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--hold-retry-ms", f->hold_retry_ms,
                 "A job held after a store fault (disk full, I/O error) is tried again this often "
                 "(default 10000)")
      ->check(CLI::Range(100u, 86400000u));
  app.add_option("--max-store-bytes", f->max_store_bytes,
                 "The job store's size at most, e.g. 10G; reaching it holds running jobs as a "
                 "full disk does (default 0: no limit)")
      ->transform(CLI::AsSizeValue(false))
      ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 50));
  app.add_option("--checkpoint-keep", f->checkpoint_keep,
                 "Full checkpoints kept per job (default 3)")
      ->check(CLI::Range(1u, 1000000u));
  app.add_option("--checkpoint-seconds", f->checkpoint_seconds,
                 "Checkpoint at most this often; 0 = after every round (default 0)")
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--checkpoint-time-share", f->checkpoint_time_share,
                 "Share of a job's time its checkpoints (queued to committed) may take at most: "
                 "the next waits until it fits, priced as the last; 0 = no wait (default 0.05)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--max-running-jobs", f->max_running_jobs, "Jobs solved at once (default 4)")
      ->check(CLI::Range(1u, 1024u));
  app.add_option("--lease-seconds", f->lease_seconds,
                 "Time one batch should take on its agent (default 0.25)")
      ->check(CLI::Range(0.001, 3600.0));
  app.add_option("--max-agents", f->max_agents,
                 "Authenticated agents at most; more are refused (default 4096)")
      ->check(CLI::Range(1u, 1000000u));
  app.add_option("--max-unauthenticated", f->max_unauthenticated,
                 "Connections in the handshake at once; a newer one closes the oldest, and they "
                 "never count toward --max-agents (default 64)")
      ->check(CLI::Range(1u, 1000000u));
  app.add_option("--max-connections-per-agent", f->max_connections_per_agent,
                 "Authenticated connections at once under one agent name; more are refused after "
                 "their handshake (default 2)")
      ->check(CLI::Range(1u, 1000000u));
  app.add_option("--max-frame-bytes-held", f->max_frame_bytes_held,
                 "Bytes held at once in agents' frames still arriving, all connections together; "
                 "a frame that would pass it closes its connection (default 268435456, at least "
                 "16777216)")
      ->check(CLI::Range(kMinFrameBytesHeld, uint64_t{1} << 40));
  app.add_option("--local-round-rays", f->local_round_rays,
                 "Rounds of at most this many rays are computed by the master, not leased to "
                 "agents; 0 = never (default 262144)")
      ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 40));
  app.add_option("--gather-ahead-rays", f->gather_ahead_rays,
                 "The final gather's first rays, at most this many, go to agents that idle between "
                 "and at the ends of the shooting rounds; their results wait on the master, at "
                 "most about 16 bytes a ray; 0 = off (default 1048576)")
      ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 40));
  app.add_option("--keep-round-results", f->keep_round_results,
                 "Keep each accepted batch result in the store until its round's checkpoint, so "
                 "a restarted master leases only the batches it had not received (default true)");
  app.add_option("--keep-results-after", f->keep_results_after_seconds,
                 "Keep only the results accepted once a round has run this many seconds: a "
                 "shorter round is cheaper to compute again than to write (default 5)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--http", f->http,
                 "HOST:PORT of the web console (status page, /metrics); off by default; port 0 "
                 "picks a free one, written to STATE/http.addr; a non-loopback HOST needs "
                 "--http-token-file");
  app.add_option("--http-token-file", f->http_token_file,
                 "A file holding the web token (16+ characters; `radfarm secret new FILE` makes "
                 "one): needed to pause, resume or cancel from the page, and for everything "
                 "when --http is not on loopback");
  app.add_flag("--detach", f->detach,
               "Run in the background: return once the daemon is ready (store open, listeners "
               "bound, listen.addr written), printing its pid; or with its exit code when it "
               "cannot start. For scripts; under systemd, leave it out");
}

template <typename T>
void Override(const std::optional<T>& flag, T* value) {
  if (flag) *value = *flag;
}

Result<MasterConfig> ResolveConfig(const Flags& f) {
  MasterConfig c;
  if (f.config) {
    RADFARM_RETURN_IF_ERROR(ReadMasterConfigFile(*f.config, &c));
  }
  Override(f.listen, &c.listen);
  Override(f.state_dir, &c.state_dir);
  Override(f.secret_file, &c.secret_file);
  Override(f.control, &c.control);
  Override(f.log_level, &c.log_level);
  Override(f.heartbeat_ms, &c.heartbeat_ms);
  Override(f.agent_timeout_ms, &c.agent_timeout_ms);
  Override(f.handshake_timeout_ms, &c.handshake_timeout_ms);
  Override(f.control_timeout_ms, &c.control_timeout_ms);
  Override(f.hold_retry_ms, &c.hold_retry_ms);
  Override(f.max_store_bytes, &c.max_store_bytes);
  Override(f.checkpoint_keep, &c.checkpoint_keep);
  Override(f.checkpoint_seconds, &c.checkpoint_seconds);
  Override(f.checkpoint_time_share, &c.checkpoint_time_share);
  Override(f.max_running_jobs, &c.max_running_jobs);
  Override(f.lease_seconds, &c.lease_seconds);
  Override(f.max_agents, &c.max_agents);
  Override(f.blocklist_seconds, &c.blocklist_seconds);
  Override(f.verify_fraction, &c.verify_fraction);
  Override(f.max_unauthenticated, &c.max_unauthenticated);
  Override(f.max_connections_per_agent, &c.max_connections_per_agent);
  Override(f.max_frame_bytes_held, &c.max_frame_bytes_held);
  Override(f.local_round_rays, &c.local_round_rays);
  Override(f.gather_ahead_rays, &c.gather_ahead_rays);
  Override(f.keep_round_results, &c.keep_round_results);
  Override(f.keep_results_after_seconds, &c.keep_results_after_seconds);
  Override(f.http, &c.http);
  Override(f.http_token_file, &c.http_token_file);
  RADFARM_RETURN_IF_ERROR(CheckMasterConfig(c));
  return c;
}

Result<protocol::FarmSecret> ReadSecret(const std::string& path) {
  Result<std::string> text = ReadTextFile(path);
  if (!text) return Error{"secret file " + text.error()};
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::FromHex(*text);
  if (!secret) return Error{path + ": " + secret.error()};
  struct stat st {};
  if (stat(path.c_str(), &st) == 0 && (st.st_mode & 077) != 0) {
    loop::LogLine(loop::LogLevel::kWarning, "master")
        << path << ": the secret is readable by other users (chmod 600 it)";
  }
  return secret;
}

loop::LogLevel ParseLevel(const std::string& name) {
  if (name == "debug") return loop::LogLevel::kDebug;
  if (name == "warning") return loop::LogLevel::kWarning;
  if (name == "error") return loop::LogLevel::kError;
  return loop::LogLevel::kInfo;
}

// `detached` (with --detach) is told once the master is ready.
int Run(const MasterConfig& config, std::optional<Detached> detached) {
  loop::SetMinLogLevel(ParseLevel(config.log_level));
  // A peer that closes its socket while we write to it must cost that connection only: without
  // this, the write raises SIGPIPE and the default action ends the daemon.
  ::signal(SIGPIPE, SIG_IGN);
  Result<protocol::FarmSecret> secret = ReadSecret(config.secret_file);
  if (!secret) {
    std::fprintf(stderr, "radfarmd: %s\n", secret.error().c_str());
    return kExitBadInput;
  }
  loop::EventLoop loop;
  Result<std::unique_ptr<Master>> master = Master::Start(loop, config, std::move(*secret));
  if (!master) {
    std::fprintf(stderr, "radfarmd: %s\n", master.error().c_str());
    (void)loop.Close();
    return kExitFailure;
  }
  if (detached) detached->Ready();
  loop.Run();
  master->reset();
  if (Status s = loop.Close(); !s) {
    std::fprintf(stderr, "radfarmd: %s\n", s.error().c_str());
    return kExitFailure;
  }
  loop::Log(loop::LogLevel::kInfo, "master", "stopped");
  return kExitOk;
}

}  // namespace
}  // namespace radfarm::daemon

int main(int argc, char** argv) {
  CLI::App app{
      "radfarmd: the radfarm master daemon. Keeps the job queue (SQLite, in the state "
      "directory), leases ray batches to radfarm-agent processes and folds their results into "
      "each job's radiosity solution. Stop it with SIGTERM; it resumes every job on restart."};
  app.set_version_flag("--version", "radfarmd 0.1.0");
  radfarm::daemon::Flags flags;
  radfarm::daemon::AddFlags(app, &flags);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? radfarm::daemon::kExitOk : radfarm::daemon::kExitBadInput;
  }
  radfarm::Result<radfarm::daemon::MasterConfig> config = radfarm::daemon::ResolveConfig(flags);
  if (!config) {
    std::fprintf(stderr, "radfarmd: %s\n", config.error().c_str());
    return radfarm::daemon::kExitBadInput;
  }
  // With --detach the caller's process exits inside Detach.
  std::optional<radfarm::daemon::Detached> detached =
      flags.detach ? radfarm::daemon::Detached::Detach() : std::nullopt;
  if (flags.detach && !detached) return radfarm::daemon::kExitFailure;
  return radfarm::daemon::Run(*config, std::move(detached));
}
