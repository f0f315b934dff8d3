// What the file-reading fuzzers share (docs/FUZZING.md): one fuzz input holds several files (an OBJ
// and its MTL, a .gltf and its buffer), separated by kFuzzPartSeparator, and the readers under test
// get them as real files in a scratch directory made once per process.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

namespace radfarm::fuzz {

// A line of its own that no scene or job file has; the seed writer (scripts/make-fuzz-seeds) joins
// files with it.
inline constexpr std::string_view kFuzzPartSeparator = "\n----8<----\n";

// The input cut at each separator into at most `max_parts` parts (the last keeps any further
// separators); always at least one part, possibly empty.
std::vector<std::string_view> SplitFuzzInput(std::span<const uint8_t> data, size_t max_parts);

// This process's own empty directory (in /dev/shm when there is one, so writes stay in memory),
// made on the first call and removed at exit.
const std::filesystem::path& FuzzScratchDirectory();

// Replaces `path` with exactly `bytes`; aborts if it cannot, since the fuzzer would be blind.
void WriteFuzzFile(const std::filesystem::path& path, std::string_view bytes);

}  // namespace radfarm::fuzz
