#include "daemon/console/web_console.h"

#include <sys/stat.h>

#include "base/atomic_file.h"
#include "daemon/console/job_preview.h"
#include "daemon/console/web/web_access.h"
#include "loop/host_port.h"
#include "loop/log.h"

namespace radfarm::daemon {
namespace {

// The control socket's answer as an HTTP one: its JSON body, the status from its error code.
web::WebReply ToWebReply(const ControlResponse& response) {
  unsigned status = 200;
  if (!response.body.value("ok", false)) {
    const std::string code = response.body.value("code", std::string());
    status = code == "not_found"       ? 404
             : code == "invalid_state" ? 409
             : code == "bad_request"   ? 400
                                       : 500;
  }
  return {status, "application/json",
          response.body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)};
}

}  // namespace

WebConsole::WebConsole(loop::EventLoop& loop, ControlRequests& control, JobRounds& jobs,
                       StoreThread& store)
    : loop_(loop), control_(control), publisher_(loop, control, jobs, store, board_) {}

WebConsole::~WebConsole() { Stop(); }

Result<std::unique_ptr<WebConsole>> WebConsole::Start(loop::EventLoop& loop,
                                                      const MasterConfig& config,
                                                      ControlRequests& control, JobRounds& jobs,
                                                      StoreThread& store) {
  Result<loop::HostPort> address = loop::ParseHostPort(config.http, "--http");
  RADFARM_RETURN_IF_ERROR(address);
  std::string token;
  if (!config.http_token_file.empty()) {
    Result<std::string> read = web::ReadTokenFile(config.http_token_file);
    RADFARM_RETURN_IF_ERROR(read);
    token = std::move(*read);
    struct stat st {};
    if (stat(config.http_token_file.c_str(), &st) == 0 && (st.st_mode & 077) != 0) {
      loop::LogLine(loop::LogLevel::kWarning, "http")
          << config.http_token_file << ": the token is readable by other users (chmod 600 it)";
    }
  }
  std::unique_ptr<WebConsole> console(new WebConsole(loop, control, jobs, store));
  auto caller = web::LoopCaller::Create(loop);
  RADFARM_RETURN_IF_ERROR(caller);
  console->caller_ = std::move(*caller);
  auto previews = loop::WorkQueue::Create(loop, 1, "preview");
  RADFARM_RETURN_IF_ERROR(previews);
  console->previews_ = std::move(*previews);
  const bool loopback = web::IsLoopbackHost(address->host);
  const bool actions = !token.empty();
  auto routes = std::make_unique<web::WebRoutes>(web::WebAccess(loopback, std::move(token)),
                                                 console->board_, console->Handlers());
  auto server = web::HttpServer::Start(*address, std::move(routes), console->board_);
  RADFARM_RETURN_IF_ERROR(server);
  console->server_ = std::move(*server);
  if (Status s = WriteFileAtomically(config.HttpAddrPath(), console->address() + "\n"); !s) {
    return Error{s.error()};
  }
  console->publisher_.Start();
  loop::LogLine(loop::LogLevel::kInfo, "http")
      << "status page on http://" << console->address() << "/"
      << (actions ? " (pause, resume and cancel with the token)" : " (read-only: no token)");
  return console;
}

web::WebHandlers WebConsole::Handlers() {
  web::WebHandlers handlers;
  handlers.act = [this](std::string_view action, int64_t id) {
    const ControlCommand command = action == "pause"    ? ControlCommand::kPause
                                   : action == "resume" ? ControlCommand::kResume
                                                        : ControlCommand::kCancel;
    return caller_->Call(
        [this, command, id](web::LoopCaller::Reply reply) { Act(command, id, std::move(reply)); },
        kCallTimeout);
  };
  handlers.preview = [this](int64_t id) {
    return caller_->Call(
        [this, id](web::LoopCaller::Reply reply) { Preview(id, std::move(reply)); }, kCallTimeout);
  };
  return handlers;
}

void WebConsole::Act(ControlCommand command, int64_t id, web::LoopCaller::Reply reply) {
  ControlRequest request;
  request.command = command;
  request.id = id;
  control_.Handle(std::move(request), [reply](ControlResponse response) {
    if (response.body.value("ok", false)) {
      loop::LogLine(loop::LogLevel::kInfo, "http")
          << "job " << response.body["job"].value("id", int64_t{0}) << " is now "
          << response.body["job"].value("state", std::string()) << " (web console)";
    }
    reply(ToWebReply(response));
  });
}

void WebConsole::Preview(int64_t id, web::LoopCaller::Reply reply) {
  ControlRequest request;
  request.command = ControlCommand::kFetch;
  request.id = id;
  control_.Handle(std::move(request), [this, reply](ControlResponse response) {
    if (!response.body.value("ok", false)) return reply(ToWebReply(response));
    auto blob = std::make_shared<std::vector<uint8_t>>(std::move(response.attachment));
    Status s = previews_->Submit([blob] { return RenderPreviewPng(*blob); },
                                 [reply](Result<std::string> png) {
                                   if (!png) return reply(web::JsonError(500, png.error()));
                                   reply({200, "image/png", std::move(*png)});
                                 });
    if (!s) reply(web::JsonError(503, s.error()));
  });
}

void WebConsole::Stop() {
  if (stopped_) return;
  stopped_ = true;
  board_.Close();                 // event streams end
  if (caller_) caller_->Close();  // HTTP threads waiting on the loop get 503
  publisher_.Stop();
  if (server_) server_->Stop();  // joins the HTTP threads, none of them waiting now
  if (previews_) previews_->Shutdown(loop::WorkQueue::ShutdownMode::kCancel, [] {});
}

}  // namespace radfarm::daemon
