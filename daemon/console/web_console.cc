#include "daemon/console/web_console.h"

#include <sys/stat.h>

#include <mutex>
#include <optional>

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

// What the loop thread hands an HTTP thread waiting on a preview: the flight it joined for it.
// Once the HTTP thread stopped waiting (Take), the loop joins nothing more for it.
struct WebConsole::PreviewTicket {
  std::mutex mutex;
  bool taken = false;
  std::shared_ptr<PreviewFlight> flight;

  // Loop thread. False when the HTTP thread has stopped waiting.
  bool Give(std::shared_ptr<PreviewFlight> joined) {
    std::lock_guard lock(mutex);
    if (taken) return false;
    flight = std::move(joined);
    return true;
  }
  // HTTP thread, once.
  std::shared_ptr<PreviewFlight> Take() {
    std::lock_guard lock(mutex);
    taken = true;
    return std::move(flight);
  }
};

WebConsole::WebConsole(loop::EventLoop& loop, ControlRequests& control, JobRounds& jobs,
                       StoreThread& store)
    : loop_(loop),
      control_(control),
      store_(store),
      publisher_(loop, control, jobs, store, board_) {}

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
  handlers.preview = [this](int64_t id, int connection_fd) {
    return PreviewFor(id, connection_fd);
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

web::WebReply WebConsole::PreviewFor(int64_t id, int connection_fd) {
  auto ticket = std::make_shared<PreviewTicket>();
  web::WebReply joined = caller_->Call(
      [this, id, ticket](web::LoopCaller::Reply reply) {
        JoinPreview(id, ticket, std::move(reply));
      },
      kCallTimeout);
  const std::shared_ptr<PreviewFlight> flight = ticket->Take();
  if (!flight) return joined;  // no such job, no checkpoint yet, the store failed, or no answer
  std::optional<Result<std::string>> png = flight->Wait(connection_fd, kCallTimeout);
  previews_cache_->Leave(flight);
  if (!png) return web::JsonError(503, "the preview was not drawn in time");
  if (!*png) return web::JsonError(500, png->error());
  return {200, "image/png", std::move(**png)};
}

void WebConsole::JoinPreview(int64_t id, std::shared_ptr<PreviewTicket> ticket,
                             web::LoopCaller::Reply reply) {
  using Stamp = std::optional<std::pair<uint32_t, int64_t>>;
  store_.Run(
      [id](store::JobStore& s) -> Result<std::optional<Stamp>> {
        Result<std::optional<store::JobRecord>> job = s.GetJob(store::JobId(id));
        RADFARM_RETURN_IF_ERROR(job);
        if (!*job) return std::optional<Stamp>();
        Result<Stamp> stamp = s.LatestCheckpointStamp(store::JobId(id));
        RADFARM_RETURN_IF_ERROR(stamp);
        return std::optional<Stamp>(*stamp);
      },
      [this, id, ticket, reply](Result<std::optional<Stamp>> found) {
        if (!found) return reply(web::JsonError(500, found.error()));
        const std::string job = "job " + std::to_string(id);
        if (!*found) return reply(web::JsonError(404, "no " + job));
        if (!**found) return reply(web::JsonError(409, job + " has no checkpoint yet"));
        const PreviewKey key{id, (**found)->first, (**found)->second};
        PreviewCache::Joined joined = previews_cache_->Join(key);
        if (!ticket->Give(joined.flight)) {
          previews_cache_->Leave(joined.flight);  // its requester stopped waiting meanwhile
          return;
        }
        reply({202, "text/plain", "joined"});  // the HTTP thread waits on the flight now
        if (joined.compute) DrawPreview(key, std::move(joined.flight));
      });
}

void WebConsole::DrawPreview(const PreviewKey& key, std::shared_ptr<PreviewFlight> flight) {
  ControlRequest request;
  request.command = ControlCommand::kFetch;
  request.id = key.job;
  control_.Handle(std::move(request), [this, key, flight](ControlResponse response) {
    if (!response.body.value("ok", false)) {
      return previews_cache_->Finish(flight,
                                     Error{response.body.value("error", std::string("fetch"))});
    }
    auto blob = std::make_shared<std::vector<uint8_t>>(std::move(response.attachment));
    const auto start = std::chrono::steady_clock::now();
    Status s = previews_->Submit(
        [blob, flight] {
          return RenderPreviewPng(*blob, [flight] { return flight->cancelled(); });
        },
        [cache = previews_cache_, key, flight, start](Result<std::string> png) {
          const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                              std::chrono::steady_clock::now() - start)
                              .count();
          if (flight->cancelled()) {
            loop::LogLine(loop::LogLevel::kInfo, "http")
                << "job " << key.job << ": preview of round " << key.round << " dropped after "
                << ms << " ms: every request for it has gone";
          } else if (png) {
            loop::LogLine(loop::LogLevel::kInfo, "http")
                << "job " << key.job << ": preview of round " << key.round << " drawn in " << ms
                << " ms";
          }
          cache->Finish(flight, std::move(png));
        });
    if (!s) previews_cache_->Finish(flight, Error{s.error()});
  });
}

void WebConsole::Stop() {
  if (stopped_) return;
  stopped_ = true;
  board_.Close();                 // event streams end
  if (caller_) caller_->Close();  // HTTP threads waiting on the loop get 503
  previews_cache_->Close("the master is shutting down");  // and those waiting on a drawing
  publisher_.Stop();
  if (server_) server_->Stop();  // joins the HTTP threads, none of them waiting now
  if (previews_) previews_->Shutdown(loop::WorkQueue::ShutdownMode::kCancel, [] {});
}

}  // namespace radfarm::daemon
