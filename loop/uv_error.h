// Turns libuv's negative error codes into the project's Error messages.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"

namespace radfarm::loop {

// "what: connection refused (ECONNREFUSED)".
std::string UvErrorText(std::string_view what, int code);
inline Error UvError(std::string_view what, int code) { return Error{UvErrorText(what, code)}; }

}  // namespace radfarm::loop
