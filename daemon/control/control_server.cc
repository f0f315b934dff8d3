#include "daemon/control/control_server.h"

#include "base/result.h"
#include "loop/log.h"

namespace radfarm::daemon {

struct ControlServer::Client {
  uint64_t id = 0;
  std::unique_ptr<loop::FramedConnection> connection;
  std::unique_ptr<loop::Timer> request_clock;  // runs while the client owes us a request
  // A request whose attachment frame is still to come.
  std::optional<ControlRequest> awaiting_attachment;
  uint64_t attachment_bytes = 0;
  bool busy = false;          // a request is being answered
  bool close_logged = false;  // we closed it and said why
};

Result<std::unique_ptr<ControlServer>> ControlServer::Listen(loop::EventLoop& loop,
                                                             const std::string& path,
                                                             Handler handler,
                                                             ControlServerOptions options) {
  std::unique_ptr<ControlServer> server(new ControlServer(loop, std::move(handler), options));
  ControlServer* self = server.get();
  auto listener = loop::UnixListener::Listen(
      loop, path,
      [self](std::unique_ptr<loop::FramedConnection> c) { self->OnConnection(std::move(c)); });
  RADFARM_RETURN_IF_ERROR(listener);
  server->listener_ = std::move(*listener);
  return server;
}

ControlServer::ControlServer(loop::EventLoop& loop, Handler handler, ControlServerOptions options)
    : loop_(loop), handler_(std::move(handler)), options_(options) {}

ControlServer::~ControlServer() { Close(); }

void ControlServer::Close() {
  clients_.clear();
  if (listener_) listener_->Close();
}

void ControlServer::OnConnection(std::unique_ptr<loop::FramedConnection> connection) {
  auto client = std::make_unique<Client>();
  client->id = next_client_++;
  client->connection = std::move(connection);
  client->request_clock = std::make_unique<loop::Timer>(loop_);
  Client* c = client.get();
  const uint64_t id = client->id;
  clients_[id] = std::move(client);
  loop::ConnectionOptions options;
  options.max_frame_bytes = kMaxControlAttachmentBytes;  // what we send: a fetch's solution
  options.max_queued_bytes = size_t{2} * kMaxControlAttachmentBytes;
  c->connection->Start(
      options, [this, c](std::span<const uint8_t> payload) { OnFrame(*c, payload); },
      [this, id](const std::string& reason) { OnClosed(id, reason); });
  // What we read: a JSON request, until one announces an attachment (OnFrame).
  c->connection->SetMaxReceiveFrameBytes(kMaxControlJsonBytes);
  StartRequestClock(*c);
}

void ControlServer::OnClosed(uint64_t id, const std::string& reason) {
  const auto it = clients_.find(id);
  if (it == clients_.end()) return;
  // A client hanging up is normal; a frame over its limit or a socket error is worth a line.
  if (!it->second->close_logged && reason != loop::kPeerClosedReason) {
    loop::LogLine(loop::LogLevel::kWarning, "control")
        << it->second->connection->peer() << ": " << reason << "; closed";
  }
  clients_.erase(it);
}

void ControlServer::StartRequestClock(Client& client) {
  const uint64_t id = client.id;
  client.request_clock->Start(options_.request_timeout, [this, id] {
    const auto it = clients_.find(id);
    if (it == clients_.end()) return;
    Client& c = *it->second;
    const std::string what = c.awaiting_attachment
                                 ? "the announced attachment of " +
                                       std::to_string(c.attachment_bytes) + " bytes did not arrive"
                                 : "no request";
    c.close_logged = true;
    loop::LogLine(loop::LogLevel::kWarning, "control")
        << c.connection->peer() << ": " << what << " within " << options_.request_timeout.count()
        << " ms; closing";
    c.connection->Close(what + " within " + std::to_string(options_.request_timeout.count()) +
                        " ms");
  });
}

void ControlServer::Refuse(Client& client, const std::string& code, const std::string& message) {
  client.close_logged = true;
  loop::LogLine(loop::LogLevel::kWarning, "control")
      << client.connection->peer() << ": " << message << "; closing";
  const std::string text = JsonText(ControlError(code, message).body);
  (void)client.connection->Send(
      std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  client.connection->CloseAfterFlush(message);
}

void ControlServer::OnFrame(Client& client, std::span<const uint8_t> payload) {
  if (client.awaiting_attachment) {
    if (payload.size() != client.attachment_bytes) {
      Refuse(client, "bad_request",
             "attachment of " + std::to_string(payload.size()) + " bytes, announced " +
                 std::to_string(client.attachment_bytes));
      return;
    }
    ControlRequest request = std::move(*client.awaiting_attachment);
    client.awaiting_attachment.reset();
    client.connection->SetMaxReceiveFrameBytes(kMaxControlJsonBytes);
    request.attachment.assign(payload.begin(), payload.end());
    Dispatch(client, std::move(request));
    return;
  }
  if (client.busy) {
    Refuse(client, "bad_request", "a request arrived before the previous one was answered");
    return;
  }
  Result<nlohmann::json> json = ParseControlJson(payload);
  if (!json) {
    Refuse(client, "bad_request", json.error());
    return;
  }
  uint64_t attachment_bytes = 0;
  Result<ControlRequest> request = ParseControlRequest(*json, &attachment_bytes);
  if (!request) {
    // A well-formed frame with a bad request: answer, keep the connection.
    Reply(client.id, ControlError("bad_request", request.error()));
    return;
  }
  if (attachment_bytes > 0) {
    // The next frame must be exactly this long: a longer prefix closes the connection at once.
    client.attachment_bytes = attachment_bytes;
    client.awaiting_attachment = std::move(*request);
    client.connection->SetMaxReceiveFrameBytes(static_cast<uint32_t>(attachment_bytes));
    return;
  }
  Dispatch(client, std::move(*request));
}

void ControlServer::Dispatch(Client& client, ControlRequest request) {
  client.busy = true;
  client.request_clock->Stop();  // our turn: the client waits for the answer
  const uint64_t id = client.id;
  handler_(std::move(request),
           [this, id](ControlResponse response) { Reply(id, std::move(response)); });
}

void ControlServer::Reply(uint64_t client_id, ControlResponse response) {
  const auto it = clients_.find(client_id);
  if (it == clients_.end()) return;  // the client left before the answer
  Client& client = *it->second;
  client.busy = false;
  StartRequestClock(client);
  if (!response.attachment.empty()) {
    response.body["attachment_bytes"] = response.attachment.size();
  }
  const std::string text = JsonText(response.body);
  (void)client.connection->Send(
      std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  if (!response.attachment.empty()) (void)client.connection->Send(std::move(response.attachment));
}

}  // namespace radfarm::daemon
