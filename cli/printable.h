// Text from the master made safe to print on a terminal: a job's name or error could otherwise
// carry escape sequences that move the cursor, retitle the window or rewrite what was printed.
#pragma once

#include <string>
#include <string_view>

namespace radfarm {

// `text` with every control character escaped: C0 controls and DEL as "\xNN", C1 controls
// (U+0080 to U+009F) as "\u00NN", bytes that are not UTF-8 as "\xNN". Printable UTF-8 passes
// unchanged.
std::string Printable(std::string_view text);

}  // namespace radfarm
