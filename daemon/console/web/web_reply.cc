#include "daemon/console/web/web_reply.h"

#include <nlohmann/json.hpp>

namespace radfarm::web {

WebReply JsonError(unsigned status, const std::string& message) {
  return {status, "application/json", nlohmann::json{{"ok", false}, {"error", message}}.dump()};
}

}  // namespace radfarm::web
