// Reading a whole text file and cutting it into lines and whitespace-separated words, shared by the
// OBJ and MTL line indexes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace radfarm {

// Input files are read whole into memory, so their size is checked before the first byte is read:
// 1 GiB by default, as large as a job bundle may be (protocol::kDefaultMaxSceneBytes).
inline constexpr uint64_t kDefaultMaxInputFileBytes = uint64_t{1} << 30;

// The file's bytes. Errors: "path: cannot open: <reason>" when it is missing or unreadable;
// "path: cannot open: not a regular file (a FIFO)" for a device, FIFO, socket or directory (they
// would hang the reader or never end: /dev/zero, /dev/urandom); "path: the file is N bytes, over
// the limit of M bytes" when it is larger than `max_bytes`, decided from its size alone.
Result<std::string> ReadTextFile(const std::string& path,
                                 uint64_t max_bytes = kDefaultMaxInputFileBytes);
// The same for a file already open as `fd` (the caller keeps it), `path` naming it in errors: for
// callers that check what they opened before reading it.
Result<std::string> ReadOpenFile(int fd, const std::string& path,
                                 uint64_t max_bytes = kDefaultMaxInputFileBytes);
// open(2) as ReadTextFile opens (read-only, close-on-exec, never waiting on a FIFO); -1 and errno
// on failure.
int OpenForReading(const std::string& path);

// Splits at "\n", "\r\n" or a lone "\r", the same line breaks tinyobjloader honours, so line
// numbers agree with it. The views point into `text`.
std::vector<std::string_view> SplitLines(std::string_view text);

// Overwrites every '#' comment, up to its line break, with spaces. tinyobjloader only skips whole
// comment lines and fails on "f 1 2 3 # note"; blanking keeps lengths, so line numbers still agree.
void BlankComments(std::string* text);

// The words of one line, separated by spaces or tabs.
std::vector<std::string_view> SplitWords(std::string_view line);

// Parses a whole word as a decimal floating-point number ("+1", ".5", "1e3"; also "nan" and "inf",
// which callers reject as needed; a number too large for a double gives +-inf). False if the word
// is not entirely a number.
bool ParseDouble(std::string_view word, double* value);

// Parses a whole word as a decimal integer with optional sign. False otherwise or on overflow.
bool ParseInt(std::string_view word, long long* value);

// Checks that words[1..] are between `min` and `max` finite numbers; words[0] is the statement's
// keyword. Errors read "path:line: 'Kd': cannot parse 'abc' as a number" and the like.
Status CheckNumberWords(const std::string& path, uint32_t line,
                        const std::vector<std::string_view>& words, size_t min, size_t max);

}  // namespace radfarm
