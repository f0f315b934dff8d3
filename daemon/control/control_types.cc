#include "daemon/control/control_types.h"

namespace radfarm::daemon {

ControlResponse ControlError(const std::string& code, const std::string& message) {
  return {nlohmann::json{{"ok", false}, {"error", message}, {"code", code}}, {}};
}

std::string JsonText(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace radfarm::daemon
