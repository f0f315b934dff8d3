// The control socket's request parsing on its own (docs/CONTROL.md): a request frame's bytes in, a
// checked ControlRequest or an error out. No event loop, no sockets, so the control server and the
// control request fuzzer (daemon/fuzz/) run the same code.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>

#include "base/result.h"
#include "daemon/control/control_types.h"

namespace radfarm::daemon {

inline constexpr uint32_t kMaxControlJsonBytes = 1u << 20;
inline constexpr uint32_t kMaxControlAttachmentBytes = 1u << 30;

// A request frame's JSON. Any bytes are answered: invalid JSON, invalid UTF-8 inside strings and
// trailing bytes are the error "the request is not valid JSON", never an exception.
Result<nlohmann::json> ParseControlJson(std::span<const uint8_t> payload);

// Checks one request's JSON (docs/CONTROL.md); errors say which key is wrong. `attachment_bytes`
// is set to the size of the attachment frame that must follow (submit), else 0.
Result<ControlRequest> ParseControlRequest(const nlohmann::json& json, uint64_t* attachment_bytes);

}  // namespace radfarm::daemon
