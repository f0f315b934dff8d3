// Atomic file replacement shared by every writer: the bytes go to a temporary file in the target's
// directory, are flushed to disk, and the temporary is renamed over the target. A reader (or a farm
// agent polling for results) therefore sees either the old file or the complete new one.
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"

namespace radfarm {

// Writes `contents` to `path` atomically. Errors name `path` and the failing step; on error no
// temporary file is left behind and an existing file at `path` is untouched.
Status WriteFileAtomically(const std::string& path, std::string_view contents);

// Whether a file name (without its directory) is one of WriteFileAtomically's temporaries
// ("NAME.tmp.PID.N"), e.g. left behind by a writer that crashed, for cleanups at start-up.
bool IsAtomicFileTemporary(std::string_view name);

}  // namespace radfarm
