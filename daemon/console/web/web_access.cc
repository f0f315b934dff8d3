#include "daemon/console/web/web_access.h"

#include <arpa/inet.h>
#include <sodium.h>
#include <sys/stat.h>

#include <cctype>
#include <cstdlib>

#include "base/text_file.h"

namespace radfarm::web {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool SameSecret(std::string_view a, std::string_view b) {
  if (a.size() != b.size() || a.empty()) return false;
  return sodium_memcmp(a.data(), b.data(), a.size()) == 0;
}

// "host", "host:port", "[v6]", "[v6]:port" -> host.
std::string_view HostOf(std::string_view header) {
  if (!header.empty() && header.front() == '[') {
    const size_t close = header.find(']');
    return close == std::string_view::npos ? std::string_view() : header.substr(1, close - 1);
  }
  const size_t colon = header.find(':');
  return colon == std::string_view::npos ? header : header.substr(0, colon);
}

}  // namespace

bool IsLoopbackHost(std::string_view host) {
  if (host == "localhost") return true;
  const std::string text(host);
  in_addr v4{};
  if (inet_pton(AF_INET, text.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  in6_addr v6{};
  if (inet_pton(AF_INET6, text.c_str(), &v6) == 1) return IN6_IS_ADDR_LOOPBACK(&v6);
  return false;
}

Result<std::string> ReadTokenFile(const std::string& path) {
  Result<std::string> text = ReadTextFile(path);
  if (!text) return Error{"token file " + text.error()};
  const std::string_view token = Trim(*text);
  if (token.size() < 16) return Error{path + ": the token must be at least 16 characters"};
  for (char c : token) {
    if (std::isspace(static_cast<unsigned char>(c)) || !std::isprint(static_cast<unsigned char>(c)))
      return Error{path + ": the token must be one line of printable characters without spaces"};
  }
  return std::string(token);
}

WebAccess::WebAccess(bool loopback, std::string token)
    : loopback_(loopback), token_(std::move(token)) {
  if (sodium_init() < 0) std::abort();  // libsodium cannot work at all; nothing to fall back on
}

bool WebAccess::HostAllowed(std::string_view host_header) const {
  if (!loopback_ || host_header.empty()) return true;
  return IsLoopbackHost(HostOf(host_header));
}

std::string_view WebAccess::BearerOf(std::string_view authorization) {
  constexpr std::string_view kBearer = "Bearer ";
  if (authorization.substr(0, kBearer.size()) != kBearer) return {};
  return Trim(authorization.substr(kBearer.size()));
}

bool WebAccess::BearerValid(std::string_view authorization) const {
  return has_token() && SameSecret(BearerOf(authorization), token_);
}

bool WebAccess::TokenMatches(std::string_view token) const {
  return has_token() && SameSecret(Trim(token), token_);
}

}  // namespace radfarm::web
