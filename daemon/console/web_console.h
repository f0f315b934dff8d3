// WebConsole: the master's web console (--http; docs/OPERATIONS.md, "The status page"): the
// status page, its server-sent events, /metrics, job previews and pause/resume/cancel.
//
// It joins the web library (daemon/console/web/: the HTTP server on its own threads, the access
// rules, the page) to the master without letting HTTP near the loop's state:
//   loop thread -> HTTP threads: StatusPublisher publishes immutable snapshots on a StatusBoard;
//   HTTP threads -> loop thread: actions and previews go through a LoopCaller (a uv_async queue)
//     to ControlRequests::Handle, the control socket's own code for pause, resume, cancel and
//     fetch; a preview is then drawn on the console's own preview thread.
//
// Previews (preview_cache.h): the HTTP thread asks the loop for the job's latest checkpoint (a
// small store query) and joins the PreviewCache's flight of that checkpoint; only a new flight
// fetches the solution and draws it. The HTTP thread then waits on the flight and on its client's
// socket: a client that goes leaves the flight, and a flight every client left is cancelled.
//
// Loop thread: Start, Stop. Stop closes the board and the caller (so no HTTP thread waits on the
// loop), then joins the HTTP threads; the object must outlive the master's store drain.
#pragma once

#include <memory>
#include <string>

#include "base/result.h"
#include "daemon/config/master_config.h"
#include "daemon/console/preview_cache.h"
#include "daemon/console/status_publisher.h"
#include "daemon/console/web/http_server.h"
#include "daemon/console/web/loop_caller.h"
#include "daemon/console/web/status_board.h"
#include "daemon/control/control_requests.h"
#include "daemon/jobs/job_rounds.h"
#include "daemon/jobs/store_thread.h"
#include "loop/event_loop.h"
#include "loop/work_queue.h"

namespace radfarm::daemon {

class WebConsole {
 public:
  // How long an HTTP thread waits for the loop to answer an action or a preview.
  static constexpr std::chrono::seconds kCallTimeout{60};

  // Reads the token file, binds config.http, writes STATE/http.addr, starts publishing.
  static Result<std::unique_ptr<WebConsole>> Start(loop::EventLoop& loop,
                                                   const MasterConfig& config,
                                                   ControlRequests& control, JobRounds& jobs,
                                                   StoreThread& store);
  WebConsole(const WebConsole&) = delete;
  WebConsole& operator=(const WebConsole&) = delete;
  ~WebConsole();

  const std::string& address() const { return server_->address(); }
  void Stop();

 private:
  WebConsole(loop::EventLoop& loop, ControlRequests& control, JobRounds& jobs, StoreThread& store);
  web::WebHandlers Handlers();
  // On the loop thread: `command` of job `id` through ControlRequests.
  void Act(ControlCommand command, int64_t id, web::LoopCaller::Reply reply);
  // HTTP thread: job `id`'s preview for the client on `connection_fd`.
  web::WebReply PreviewFor(int64_t id, int connection_fd);
  struct PreviewTicket;
  // On the loop thread: finds job `id`'s latest checkpoint, joins its flight into `ticket`.
  void JoinPreview(int64_t id, std::shared_ptr<PreviewTicket> ticket, web::LoopCaller::Reply reply);
  // On the loop thread: fetches the solution and draws it on the preview thread.
  void DrawPreview(const PreviewKey& key, std::shared_ptr<PreviewFlight> flight);

  loop::EventLoop& loop_;
  ControlRequests& control_;
  StoreThread& store_;
  // Shared with the preview thread's callbacks, which may run after Stop.
  std::shared_ptr<PreviewCache> previews_cache_ = std::make_shared<PreviewCache>();
  web::StatusBoard board_;
  std::unique_ptr<web::LoopCaller> caller_;
  std::unique_ptr<loop::WorkQueue> previews_;
  StatusPublisher publisher_;
  std::unique_ptr<web::HttpServer> server_;
  bool stopped_ = false;
};

}  // namespace radfarm::daemon
