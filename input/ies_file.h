// IES photometric files (ANSI/IES LM-63, the 1991, 1995 and 2002 formats): a luminaire's candela
// distribution as its manufacturer measured it. Type C photometry only (vertical angles from the
// nadir, horizontal around it: core/candela_table.h), the type of nearly every interior luminaire;
// TILT=NONE only (a lamp whose output changes with its tilt names a tilt table this reader
// refuses).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.h"
#include "core/candela_table.h"

namespace radfarm {

// An IES file is a few kilobytes; a megabyte holds the largest table a goniophotometer writes.
inline constexpr uint64_t kMaxIesFileBytes = uint64_t{1} << 20;

struct IesPhotometry {
  std::string format;  // "LM-63-2002", "LM-63-1995" or "LM-63-1991"
  // The keyword lines in file order, "[MANUFAC]" as "MANUFAC"; a 1995 or 1991 file's free text
  // lines are kept with an empty keyword.
  std::vector<std::pair<std::string, std::string>> keywords;
  int lamps = 1;
  double lumens_per_lamp = -1;  // -1: absolute photometry (the candela are the luminaire's own)
  double multiplier = 1;        // the file's candela multiplier
  double ballast_factor = 1;    // with a 1995 file's ballast-lamp factor folded in
  double input_watts = 0;
  // The luminous opening in metres (converted from feet when the file is in feet); LM-63's sign
  // conventions kept: 0 a point, negative a round opening.
  double width = 0;
  double length = 0;
  double height = 0;
  // Candela with the multiplier and ballast factor applied: what the luminaire emits.
  CandelaTable table;
};

// Parses the file's text; `path` names it in errors: "path:12: the candela multiplier 'x' is not
// a number", "path:3: TILT=INCLUDE is not supported: ...", "path:9: photometric type 2 (type B)
// is not supported: only type C", "path:14: the file ends inside the candela table (120 of 222
// values)". Every number is checked: counts positive and bounded, angles as the table requires,
// candela finite and >= 0, nothing after the table.
Result<IesPhotometry> ParseIes(std::string_view text, const std::string& path);

}  // namespace radfarm
