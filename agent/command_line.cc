#include "agent/command_line.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "agent/config_file.h"
#include "agent/exit_codes.h"
#include "base/result.h"
#include "protocol/message_checks.h"

namespace radfarm::agent {
namespace {

// The raw flag values; an option's count() says whether it was given.
struct Flags {
  std::string master, master_file, secret_file, state_dir, name, config, log_level, idle_source;
  unsigned threads = 0;
  double slowdown = 1, exit_when_idle = 0;
};

void AddFlags(CLI::App& app, Flags* f) {
  app.add_option("--master", f->master, "HOST:PORT of the master daemon radfarmd");
  app.add_option(
      "--master-file", f->master_file,
      "Read HOST:PORT from FILE (the master's STATE_DIR/listen.addr) before every "
      "connection attempt: waits for the file, and follows a master restarted on another "
      "port");
  app.add_option("--secret-file", f->secret_file, "File holding the farm secret in hex");
  app.add_option("--state-dir", f->state_dir,
                 "Directory for fetched scenes (default: keep them in memory only)");
  app.add_option("--threads", f->threads, "Batch worker threads (default: all cores)")
      ->check(CLI::Range(1u, kMaxThreads));
  app.add_option("--name", f->name,
                 "Name shown in the master's logs (default: the host name, sanitised)");
  app.add_option("--config", f->config, "TOML file with the same settings (flags override it)");
  app.add_option("--log-level", f->log_level, "debug, info, warning or error (default info)")
      ->check(CLI::IsMember({"debug", "info", "warning", "error"}));
  app.add_option("--slowdown", f->slowdown,
                 "F >= 1: hold each result (F-1) x its compute time, to simulate a slower machine")
      ->check(CLI::Range(1.0, 1e9));
  app.add_option("--exit-when-idle", f->exit_when_idle,
                 "Exit 0 after SECONDS with no lease held, connected or not (no master reachable)")
      ->check(CLI::PositiveNumber);
  app.add_option("--idle-source", f->idle_source,
                 "For tests and operations: read the user's activity from FILE ('idle' or 'busy') "
                 "instead of logind; needs the config file's [idle] policy");
}

// The flags the user gave, checked.
Result<AgentOptions> OptionsFromFlags(const CLI::App& app, const Flags& f) {
  AgentOptions options;
  auto given = [&app](const char* flag) { return app.get_option(flag)->count() > 0; };
  if (given("--master")) {
    Result<loop::HostPort> master = ParseMasterAddress(f.master, "--master");
    RADFARM_RETURN_IF_ERROR(master);
    options.master = *master;
  }
  if (given("--master-file")) {
    if (f.master_file.empty()) return Error{"--master-file: must not be empty"};
    options.master_file = f.master_file;
  }
  if (given("--secret-file")) options.secret_file = f.secret_file;
  if (given("--state-dir")) options.state_dir = f.state_dir;
  if (given("--threads")) options.threads = f.threads;
  if (given("--name")) {
    if (!protocol::IsValidAgentName(f.name)) {
      return Error{"--name: must be 1 to 64 characters of A-Z a-z 0-9 . _ : @ -, got '" + f.name +
                   "'"};
    }
    options.name = f.name;
  }
  if (given("--log-level")) options.log_level = ParseLogLevel(f.log_level);
  if (given("--slowdown")) options.slowdown = f.slowdown;
  if (given("--exit-when-idle")) options.exit_when_idle_seconds = f.exit_when_idle;
  if (given("--idle-source")) {
    if (f.idle_source.empty()) return Error{"--idle-source: must not be empty"};
    options.idle_source = f.idle_source;
  }
  return options;
}

int Fail(const std::string& message) {
  std::fprintf(stderr, "radfarm-agent: %s\n", message.c_str());
  return kExitBadInput;
}

}  // namespace

CommandLine ParseCommandLine(int argc, char** argv) {
  CLI::App app{
      "radfarm-agent: computes ray batches for a radfarm master daemon (radfarmd). It connects to "
      "--master, proves it knows the farm secret, and runs the batches it is leased until it is "
      "told to stop or gets SIGTERM/SIGINT."};
  app.set_version_flag("--version", "radfarm-agent 0.1.0");
  Flags flags;
  AddFlags(app, &flags);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  Result<AgentOptions> from_flags = OptionsFromFlags(app, flags);
  if (!from_flags) return Fail(from_flags.error());
  AgentOptions from_file;
  if (app.get_option("--config")->count() > 0) {
    Result<AgentOptions> loaded = LoadConfigFile(flags.config);
    if (!loaded) return Fail(loaded.error());
    from_file = *loaded;
  }
  Result<AgentSettings> settings = ResolveSettings(*from_flags, from_file);
  if (!settings) return Fail(settings.error());
  return *settings;
}

}  // namespace radfarm::agent
