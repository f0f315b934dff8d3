// radfarm-agent: computes ray batches for a radfarm master daemon. agent/README.md describes the
// flags, the config file, signals, exit codes and the state directory.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <random>

#include "agent/agent.h"
#include "agent/command_line.h"
#include "agent/exit_codes.h"
#include "agent/scene_store.h"
#include "agent/secret_file.h"
#include "loop/event_loop.h"
#include "loop/log.h"
#include "service/service_notifier.h"

namespace radfarm::agent {
namespace {

int Fail(int code, const std::string& message) {
  std::fprintf(stderr, "radfarm-agent: %s\n", message.c_str());
  return code;
}

uint64_t JitterSeed() {
  std::random_device random;
  return (uint64_t{random()} << 32) ^ random() ^ static_cast<uint64_t>(getpid());
}

int Run(AgentSettings settings) {
  loop::SetMinLogLevel(settings.log_level);
  Result<protocol::FarmSecret> secret = ReadSecretFile(settings.secret_file);
  if (!secret) return Fail(kExitBadInput, secret.error());
  std::optional<SceneStore> store;
  if (!settings.state_dir.empty()) {
    Result<SceneStore> opened = SceneStore::Open(settings.state_dir);
    if (!opened) return Fail(kExitBadInput, opened.error());
    store = std::move(opened).value();
  }
  // A master that vanishes mid-write must give EPIPE, not kill the agent.
  std::signal(SIGPIPE, SIG_IGN);

  loop::EventLoop loop;
  // READY=1 once Start() succeeded, STATUS= lines, STOPPING=1; no-ops without NOTIFY_SOCKET.
  auto systemd = std::make_unique<service::ServiceNotifier>(loop);
  auto agent = std::make_unique<Agent>(loop, std::move(settings), std::move(secret).value(),
                                       std::move(store), JitterSeed(), systemd.get());
  if (Status started = agent->Start(); !started) {
    agent.reset();
    systemd.reset();
    (void)loop.Close();
    return Fail(kExitFailure, started.error());
  }
  loop.Run();
  if (agent->busy()) {
    // A batch (or a scene build) is still running and cannot be interrupted; its lease has been
    // returned. Leave without joining its worker: _exit skips destructors and atexit handlers.
    loop::Log(loop::LogLevel::kInfo, "agent", "exiting without waiting for running batches");
    _exit(kExitOk);
  }
  agent.reset();
  systemd.reset();
  if (Status closed = loop.Close(); !closed) return Fail(kExitFailure, closed.error());
  loop::Log(loop::LogLevel::kInfo, "agent", "exited");
  return kExitOk;
}

}  // namespace
}  // namespace radfarm::agent

int main(int argc, char** argv) {
  radfarm::agent::CommandLine command_line = radfarm::agent::ParseCommandLine(argc, argv);
  if (const int* code = std::get_if<int>(&command_line)) return *code;
  return radfarm::agent::Run(std::get<radfarm::agent::AgentSettings>(std::move(command_line)));
}
