// WebReply: one HTTP answer as the web console's handlers make it.
#pragma once

#include <string>

namespace radfarm::web {

struct WebReply {
  unsigned status = 200;
  std::string content_type = "application/json";
  std::string body;
};

// {"ok": false, "error": message} with `status`.
WebReply JsonError(unsigned status, const std::string& message);

}  // namespace radfarm::web
