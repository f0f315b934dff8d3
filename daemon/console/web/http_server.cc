#include "daemon/console/web/http_server.h"

#include <microhttpd.h>
#include <netdb.h>
#include <sys/socket.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <utility>

#include "daemon/console/web/event_stream.h"
#include "loop/socket_address.h"

namespace radfarm::web {

namespace {

constexpr size_t kMaxBodyBytes = 4096;  // the only body is the login's {"token": "..."}

// Sent with every response: the page loads nothing from elsewhere (its previews are blob: URLs of
// its own fetches), is never framed, never cached.
constexpr std::pair<const char*, const char*> kCommonHeaders[] = {
    {"Content-Security-Policy",
     "default-src 'self'; img-src 'self' blob:; frame-ancestors 'none'; base-uri 'none'; "
     "form-action 'none'"},
    {"X-Content-Type-Options", "nosniff"},
    {"Referrer-Policy", "no-referrer"},
    {"Cache-Control", "no-store"},
};

std::string Header(MHD_Connection* c, const char* name) {
  const char* value = MHD_lookup_connection_value(c, MHD_HEADER_KIND, name);
  return value ? value : "";
}

// The client's IP address, without its port; "" if libmicrohttpd does not know it.
std::string ClientOf(MHD_Connection* c) {
  const MHD_ConnectionInfo* info = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CLIENT_ADDRESS);
  if (!info || !info->client_addr) return "";
  const sockaddr* address = info->client_addr;
  const socklen_t size =
      address->sa_family == AF_INET6 ? sizeof(sockaddr_in6) : sizeof(sockaddr_in);
  char host[NI_MAXHOST] = {};
  if (getnameinfo(address, size, host, sizeof host, nullptr, 0, NI_NUMERICHOST) != 0) return "";
  return host;
}

// libmicrohttpd's own complaints (a malformed request is two of them): rate-limited, since any
// client can make them as fast as it can send.
void LogFromMhd(void* cls, const char* format, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  std::string line(text);
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  static_cast<RateLimitedLog*>(cls)->Warn(line);
}

}  // namespace

// libmicrohttpd's callbacks, friends of HttpServer.
struct HttpGlue {
  // One request's state across the access handler's calls (headers, body pieces, the end).
  struct Pending {
    std::string body;
    bool too_big = false;
  };

  static ssize_t ReadStream(void* cls, uint64_t, char* buf, size_t max) {
    const size_t n = static_cast<EventStream*>(cls)->Read(buf, max);
    return n == 0 ? MHD_CONTENT_READER_END_OF_STREAM : static_cast<ssize_t>(n);
  }
  static void FreeStream(void* cls) { delete static_cast<EventStream*>(cls); }

  static void Completed(void* cls, MHD_Connection* c, void** req_cls, MHD_RequestTerminationCode) {
    delete static_cast<Pending*>(*req_cls);
    *req_cls = nullptr;
    auto* server = static_cast<HttpServer*>(cls);
    std::lock_guard lock(server->deadlines_mutex_);
    server->deadlines_.Waiting(c, std::chrono::steady_clock::now());
  }

  static void Connection(void* cls, MHD_Connection* c, void**,
                         MHD_ConnectionNotificationCode code) {
    auto* server = static_cast<HttpServer*>(cls);
    if (code == MHD_CONNECTION_NOTIFY_CLOSED) {
      std::lock_guard lock(server->deadlines_mutex_);
      server->deadlines_.Closed(c);
      return;
    }
    int fd = -1;
    if (const MHD_ConnectionInfo* info =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD)) {
      fd = info->connect_fd;
    }
    std::string client = ClientOf(c);
    std::lock_guard lock(server->deadlines_mutex_);
    HttpServer::Shut(
        server->deadlines_.Opened(c, std::move(client), fd, std::chrono::steady_clock::now()));
  }

  static MHD_Result OnRequest(void* cls, MHD_Connection* c, const char* url, const char* method,
                              const char*, const char* upload_data, size_t* upload_data_size,
                              void** req_cls) {
    auto* server = static_cast<HttpServer*>(cls);
    auto* pending = static_cast<Pending*>(*req_cls);
    if (!pending) {  // the headers: the body (if any) comes in later calls
      *req_cls = new Pending;
      return MHD_YES;
    }
    if (*upload_data_size > 0) {
      if (pending->body.size() + *upload_data_size > kMaxBodyBytes) {
        pending->too_big = true;
      } else {
        pending->body.append(upload_data, *upload_data_size);
      }
      *upload_data_size = 0;
      return MHD_YES;
    }
    {
      std::lock_guard lock(server->deadlines_mutex_);
      server->deadlines_.Serving(c);
    }
    WebRequest request;
    request.method = method;
    request.path = url;
    request.host = Header(c, "Host");
    request.authorization = Header(c, "Authorization");
    request.client = ClientOf(c);
    if (const MHD_ConnectionInfo* info =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD)) {
      request.connection_fd = info->connect_fd;
    }
    request.marked = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "X-Radfarm-Request");
    request.body = std::move(pending->body);
    WebResponse response = pending->too_big
                               ? WebResponse{JsonError(413, "the request body is too big"), {}}
                               : server->routes_->Handle(request);
    MHD_Response* r = nullptr;
    if (response.event_stream) {
      r = MHD_create_response_from_callback(
          MHD_SIZE_UNKNOWN, 16 * 1024, &ReadStream,
          new EventStream(server->board_, server->streams_.Join(request.client)), &FreeStream);
    } else {
      std::string& body = response.reply.body;
      r = MHD_create_response_from_buffer(body.size(), body.data(), MHD_RESPMEM_MUST_COPY);
    }
    if (!r) return MHD_NO;
    MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, response.reply.content_type.c_str());
    for (const auto& [name, value] : kCommonHeaders) MHD_add_response_header(r, name, value);
    for (const auto& [name, value] : response.headers) {
      MHD_add_response_header(r, name.c_str(), value.c_str());
    }
    const MHD_Result queued = MHD_queue_response(c, response.reply.status, r);
    MHD_destroy_response(r);
    return queued;
  }
};

HttpServer::HttpServer(std::unique_ptr<WebRoutes> routes, const StatusBoard& board,
                       const Limits& limits)
    : routes_(std::move(routes)),
      board_(board),
      limits_(limits),
      server_log_("http", "HTTP server warnings", kLogLines, limits.log_window),
      streams_(board, limits.max_event_streams, limits.max_event_streams_per_address),
      deadlines_(limits.request_deadline, limits.max_waiting, limits.max_waiting_per_address) {}

void HttpServer::Shut(const std::vector<int>& fds) {
  // shutdown, not close: libmicrohttpd still owns the descriptor and closes it after telling
  // Connection, which waits for deadlines_mutex_.
  for (const int fd : fds) {
    if (fd >= 0) shutdown(fd, SHUT_RDWR);
  }
}

void HttpServer::Reap() {
  const auto tick =
      std::min<std::chrono::milliseconds>(std::chrono::seconds(1), limits_.request_deadline / 4);
  std::unique_lock lock(deadlines_mutex_);
  while (!stopping_) {
    reaper_wake_.wait_for(lock, tick);
    Shut(deadlines_.Expired(std::chrono::steady_clock::now()));
  }
}

HttpServer::~HttpServer() { Stop(); }

Result<std::unique_ptr<HttpServer>> HttpServer::Start(const loop::HostPort& address,
                                                      std::unique_ptr<WebRoutes> routes,
                                                      const StatusBoard& board, Limits limits) {
  Result<std::vector<loop::SocketAddress>> resolved = loop::Resolve(address, true);
  if (!resolved) return Error{"--http " + address.ToString() + ": " + resolved.error()};
  if (resolved->empty()) return Error{"--http " + address.ToString() + ": no address"};
  const loop::SocketAddress& bind = resolved->front();
  std::unique_ptr<HttpServer> server(new HttpServer(std::move(routes), board, limits));
  unsigned flags =
      MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_ERROR_LOG;
  if (bind.family() == AF_INET6) flags |= MHD_USE_IPv6;
  server->daemon_ = MHD_start_daemon(
      flags, bind.port(), nullptr, nullptr, &HttpGlue::OnRequest, server.get(),
      MHD_OPTION_EXTERNAL_LOGGER, &LogFromMhd, &server->server_log_, MHD_OPTION_SOCK_ADDR,
      bind.get(), MHD_OPTION_CONNECTION_LIMIT, kMaxConnections, MHD_OPTION_CONNECTION_TIMEOUT,
      unsigned{60}, MHD_OPTION_NOTIFY_COMPLETED, &HttpGlue::Completed, server.get(),
      MHD_OPTION_NOTIFY_CONNECTION, &HttpGlue::Connection, server.get(), MHD_OPTION_END);
  if (!server->daemon_) {
    return Error{"--http " + address.ToString() + ": cannot listen (address in use?)"};
  }
  const MHD_DaemonInfo* info = MHD_get_daemon_info(server->daemon_, MHD_DAEMON_INFO_BIND_PORT);
  loop::HostPort bound{address.host, info ? info->port : address.port};
  server->address_ = bound.ToString();
  server->reaper_ = std::thread([s = server.get()] { s->Reap(); });
  return server;
}

void HttpServer::Stop() {
  if (reaper_.joinable()) {
    {
      std::lock_guard lock(deadlines_mutex_);
      stopping_ = true;
    }
    reaper_wake_.notify_all();
    reaper_.join();
  }
  if (daemon_) MHD_stop_daemon(daemon_);
  daemon_ = nullptr;
  server_log_.Flush(std::chrono::steady_clock::now());
}

}  // namespace radfarm::web
