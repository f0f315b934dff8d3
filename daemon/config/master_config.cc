#include "daemon/config/master_config.h"

#include <filesystem>

#include "base/result.h"
#include "base/toml_file.h"
#include "base/toml_table_reader.h"
#include "daemon/console/web/web_access.h"
#include "loop/host_port.h"

namespace radfarm::daemon {

std::string MasterConfig::ControlPath() const {
  return control.empty() ? (std::filesystem::path(state_dir) / "control.sock").string() : control;
}
std::string MasterConfig::DatabasePath() const {
  return (std::filesystem::path(state_dir) / "radfarm.db").string();
}
std::string MasterConfig::ListenAddrPath() const {
  return (std::filesystem::path(state_dir) / "listen.addr").string();
}
std::string MasterConfig::HttpAddrPath() const {
  return (std::filesystem::path(state_dir) / "http.addr").string();
}

Status ReadMasterConfigFile(const std::string& path, MasterConfig* c) {
  Result<toml::table> table = ReadTomlFile(path);
  RADFARM_RETURN_IF_ERROR(table);
  TomlTableReader r(path, *table, "");
  constexpr int64_t kMaxMs = 24 * 3600 * 1000;
  constexpr int64_t kMaxLocalRoundRays = int64_t{1} << 40;
  for (Status s :
       {r.String("listen", &c->listen),
        r.String("state_dir", &c->state_dir),
        r.String("secret_file", &c->secret_file),
        r.String("control", &c->control),
        r.Integer("heartbeat_ms", 10, kMaxMs, &c->heartbeat_ms),
        r.Integer("agent_timeout_ms", 100, kMaxMs, &c->agent_timeout_ms),
        r.Integer("handshake_timeout_ms", 100, kMaxMs, &c->handshake_timeout_ms),
        r.Integer("control_timeout_ms", 100, kMaxMs, &c->control_timeout_ms),
        r.Integer("hold_retry_ms", 100, kMaxMs, &c->hold_retry_ms),
        r.Integer("max_store_bytes", 0, int64_t{1} << 50, &c->max_store_bytes),
        r.String("log_level", &c->log_level),
        r.Integer("checkpoint_keep", 1, 1000000, &c->checkpoint_keep),
        r.Real("checkpoint_seconds", Interval::AtLeast(0), &c->checkpoint_seconds),
        r.Real("checkpoint_time_share", Interval::Closed(0, 1), &c->checkpoint_time_share),
        r.Integer("max_running_jobs", 1, 1024, &c->max_running_jobs),
        r.Real("lease_seconds", Interval::Open(0, 3600), &c->lease_seconds),
        r.Integer("blocklist_seconds", 1, 7 * 24 * 3600, &c->blocklist_seconds),
        r.Real("verify_fraction", Interval{0, 1, false, false}, &c->verify_fraction),
        r.Integer("max_agents", 1, 1000000, &c->max_agents),
        r.Integer("max_unauthenticated", 1, 1000000, &c->max_unauthenticated),
        r.Integer("max_connections_per_agent", 1, 1000000, &c->max_connections_per_agent),
        r.Integer("max_frame_bytes_held", kMinFrameBytesHeld, int64_t{1} << 40,
                  &c->max_frame_bytes_held),
        r.Bool("allow_shared_secret", &c->allow_shared_secret),
        r.Integer("local_round_rays", 0, kMaxLocalRoundRays, &c->local_round_rays),
        r.Integer("gather_ahead_rays", 0, kMaxLocalRoundRays, &c->gather_ahead_rays),
        r.Bool("keep_round_results", &c->keep_round_results),
        r.Real("keep_results_after_seconds", Interval::AtLeast(0), &c->keep_results_after_seconds),
        r.String("http", &c->http),
        r.String("http_token_file", &c->http_token_file)}) {
    RADFARM_RETURN_IF_ERROR(s);
  }
  RADFARM_RETURN_IF_ERROR(r.CheckNoUnknownKeys());
  RADFARM_RETURN_IF_ERROR(loop::ParseHostPort(c->listen, path + ": 'listen'"));
  return Ok{};
}

Status CheckMasterConfig(const MasterConfig& c) {
  RADFARM_RETURN_IF_ERROR(loop::ParseHostPort(c.listen, "--listen"));
  if (c.state_dir.empty()) return Error{"--state-dir: must not be empty"};
  if (c.secret_file.empty()) return Error{"--secret-file: must not be empty"};
  if (c.log_level != "debug" && c.log_level != "info" && c.log_level != "warning" &&
      c.log_level != "error") {
    return Error{"--log-level: expected debug, info, warning or error, got '" + c.log_level + "'"};
  }
  if (!c.http.empty()) {
    Result<loop::HostPort> http = loop::ParseHostPort(c.http, "--http");
    RADFARM_RETURN_IF_ERROR(http);
    if (!web::IsLoopbackHost(http->host) && c.http_token_file.empty()) {
      return Error{"--http " + c.http +
                   ": a web console outside loopback needs --http-token-file (the token every "
                   "request must then carry)"};
    }
  } else if (!c.http_token_file.empty()) {
    return Error{"--http-token-file: only with --http"};
  }
  if (c.agent_timeout_ms < 2 * c.heartbeat_ms) {
    return Error{"--agent-timeout-ms (" + std::to_string(c.agent_timeout_ms) +
                 ") must be at least twice --heartbeat-ms (" + std::to_string(c.heartbeat_ms) +
                 ")"};
  }
  return Ok{};
}

}  // namespace radfarm::daemon
