// Rot on the disk, for tests: one bit flipped in a blob column of one row of a store file.
#pragma once

#include <string>

namespace radfarm::store {

// Flips a bit in the middle of `column` of the row of `table` that `where` selects; fails the
// running test when the row or the blob is missing.
void FlipBit(const std::string& path, const std::string& table, const std::string& column,
             const std::string& where);

}  // namespace radfarm::store
