// Contact lines: where a solid stands on a face (a block on the floor), the face's patches are cut
// along the solid's footprint and the pieces under it dropped. Without the cut a patch straddling
// the footprint spreads the light it receives on its visible part over its whole area, the part
// under the block included: the visible part is drawn too dark (a shadow leak along the block's
// base) and its light too weak: such patches carry most of a floor's discretisation
// error (docs/BENCHMARKS-adaptive.md).
//
// A footprint on face F is a closed loop of edges of other faces lying in F's plane, inside F's
// outline and not along it (the walls of a room stand on its floor along the floor's outline:
// that is a crease, not a contact), each belonging to a face that rises in front of F and faces
// away from the loop's inside (a room's walls standing in a ring on a larger ground face into the
// ring: the ground inside is the room's floor, not covered). Only convex loops are cut (a box
// standing on the floor; a concave base, or one whose loop is broken because a side was dropped as
// hidden, is left uncut).
//
// A sheet over a face covers it too: a face parallel to F and facing the same way (its back toward
// F), in front of F by at most kSheetGap of its size (the square root of its area), or by up to
// a few patch sizes while that is at most kSheetGapFar of its size, its outline inside F's. The
// Cornell box's light hangs 0.8 mm under the ceiling, the seed room's 1 mm: the ceiling above it
// sees only the light's back through a slit, so it is dark, and patches across the light's outline,
// or vertices averaged across it, smear that step into the lit ceiling around it (a dark ring in
// the image). F is cut along the sheet's outline, but the part under it is kept, as a surface of
// its own (PatchMesh::Build): rays through the slit must still meet the ceiling, and its own
// surface keeps its darkness out of the vertices around. A sheet facing F (a light shining on it, a
// cabinet's back 10 cm from a wall) covers nothing: cutting the wall behind a cabinet along its
// outline did not help (docs/BENCHMARKS-accuracy.md): the error there is the coarse solution's in
// the crevice.
#pragma once

#include <cstddef>
#include <vector>

#include "core/vec3.h"
#include "mesh/clean_faces.h"
#include "mesh/polygon_split.h"

namespace radfarm {

using Footprint = std::vector<Vec3>;  // convex, counter-clockwise about the face's normal

// The largest gap under a covering sheet, as a share of the square root of its area: always
// kSheetGap, and up to FindCoveringSheets' reach while under kSheetGapFar.
inline constexpr double kSheetGap = 0.02;
inline constexpr double kSheetGapFar = 0.5;

// For each face, the footprints of what stands on it; solids side by side whose outlines share
// edges there (a wall's parts and the lintels between them, on a ceiling) each give their own.
std::vector<std::vector<Footprint>> FindFootprints(const std::vector<CleanFace>& faces, double tol);

// For each face, the outlines of the sheets covering it, projected onto it; `reach` (a few patch
// sizes) is how far a large sheet may hang.
std::vector<std::vector<Footprint>> FindCoveringSheets(const std::vector<CleanFace>& faces,
                                                       double tol, double reach);

// Cuts `pieces` (convex, in a face with unit normal `normal`) along `footprints`: pieces outside
// stay as they are, pieces inside are dropped, pieces across a footprint's edge become the convex
// parts outside it (triangles, or quads where a part has four corners). Parts under `min_area`
// are dropped. Returns the area under the footprints, which is dropped, or with `covered` moved
// there (as convex pieces) instead.
double CutFootprints(const std::vector<Footprint>& footprints, const Vec3& normal, double tol,
                     double min_area, std::vector<PieceCorners>* pieces,
                     std::vector<PieceCorners>* covered = nullptr);

}  // namespace radfarm
