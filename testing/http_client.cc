#include "testing/http_client.h"

#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cctype>
#include <functional>

#include "loop/host_port.h"
#include "loop/socket_address.h"

namespace radfarm::testing {
namespace {

using Clock = std::chrono::steady_clock;

class Connection {
 public:
  ~Connection() {
    if (fd_ >= 0) ::close(fd_);
  }
  Status Open(const std::string& address) {
    Result<loop::HostPort> hp = loop::ParseHostPort(address, "address");
    RADFARM_RETURN_IF_ERROR(hp);
    Result<loop::SocketAddress> sa = loop::SocketAddress::FromIpLiteral(*hp);
    RADFARM_RETURN_IF_ERROR(sa);
    fd_ = ::socket(sa->family(), SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) return Error{"socket failed"};
    const socklen_t size = sa->family() == AF_INET6 ? sizeof(sockaddr_in6) : sizeof(sockaddr_in);
    if (::connect(fd_, sa->get(), size) != 0) return Error{"cannot connect to " + address};
    return Ok{};
  }
  Status SendAll(const std::string& data) {
    size_t sent = 0;
    while (sent < data.size()) {
      const ssize_t n = ::send(fd_, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return Error{"send failed"};
      sent += size_t(n);
    }
    return Ok{};
  }
  // Appends what arrives to *out until `stop(*out)`, the end of the stream or `deadline`.
  Status Read(std::string* out, Clock::time_point deadline,
              const std::function<bool(const std::string&)>& stop) {
    char buffer[16384];
    while (!stop(*out)) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      if (left.count() <= 0) return Error{"timed out reading the response"};
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, int(left.count())) <= 0) continue;
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n < 0) return Error{"recv failed"};
      if (n == 0) return Ok{};
      out->append(buffer, size_t(n));
    }
    return Ok{};
  }

 private:
  int fd_ = -1;
};

std::string RequestText(const std::string& address, const std::string& method,
                        const std::string& path, const std::vector<std::string>& headers,
                        const std::string& body) {
  std::string text = method + " " + path + " HTTP/1.0\r\n";
  bool host = false;
  for (const std::string& h : headers) {
    host = host || h.rfind("Host:", 0) == 0;
    text += h + "\r\n";
  }
  if (!host) text += "Host: " + address + "\r\n";
  if (!body.empty()) text += "Content-Length: " + std::to_string(body.size()) + "\r\n";
  return text + "\r\n" + body;
}

}  // namespace

Result<HttpResponse> HttpRequest(const std::string& address, const std::string& method,
                                 const std::string& path, const std::vector<std::string>& headers,
                                 const std::string& body, std::chrono::milliseconds timeout) {
  Connection c;
  RADFARM_RETURN_IF_ERROR(c.Open(address));
  RADFARM_RETURN_IF_ERROR(c.SendAll(RequestText(address, method, path, headers, body)));
  std::string raw;
  RADFARM_RETURN_IF_ERROR(c.Read(&raw, Clock::now() + timeout, [](const std::string&) {
    return false;  // to the end
  }));
  const size_t head_end = raw.find("\r\n\r\n");
  if (raw.rfind("HTTP/1.", 0) != 0 || head_end == std::string::npos) {
    return Error{"not an HTTP response: " + raw.substr(0, 80)};
  }
  HttpResponse response;
  response.status = std::stoi(raw.substr(9, 3));
  size_t line = raw.find("\r\n") + 2;
  while (line < head_end) {
    const size_t end = raw.find("\r\n", line);
    const std::string header = raw.substr(line, end - line);
    const size_t colon = header.find(':');
    if (colon != std::string::npos) {
      std::string name = header.substr(0, colon);
      for (char& ch : name) ch = char(std::tolower(static_cast<unsigned char>(ch)));
      size_t value = colon + 1;
      while (value < header.size() && header[value] == ' ') ++value;
      response.headers[name] = header.substr(value);
    }
    line = end + 2;
  }
  response.body = raw.substr(head_end + 4);
  return response;
}

Result<std::string> HttpReadUntil(const std::string& address, const std::string& path,
                                  const std::string& marker, std::chrono::milliseconds timeout) {
  Connection c;
  RADFARM_RETURN_IF_ERROR(c.Open(address));
  RADFARM_RETURN_IF_ERROR(c.SendAll(RequestText(address, "GET", path, {}, "")));
  std::string raw;
  RADFARM_RETURN_IF_ERROR(c.Read(&raw, Clock::now() + timeout, [&](const std::string& text) {
    return text.find(marker) != std::string::npos;
  }));
  if (raw.find(marker) == std::string::npos) {
    return Error{"the stream ended without '" + marker + "': " + raw.substr(0, 200)};
  }
  return raw;
}

}  // namespace radfarm::testing
