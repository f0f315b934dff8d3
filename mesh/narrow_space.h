// Narrow spaces: a surface's light bends over about the distance to the surfaces it sees (the
// rule the automatic patch size applies per face, auto_patch_size.h). Where part of a face looks
// into a narrow space (the wall behind a cabinet 10 cm from it, the cabinet's back, the floor
// between them), its light falls off over a few centimetres; a patch the
// face's size averages that fall-off away, and display points there gather from those averages:
// the crevices behind cabinets hold most of the display's worst points
// (docs/BENCHMARKS-accuracy.md), and a finer mesh all over would fix them at many times the
// patches.
//
// So each piece of a face is probed from its centre (FreePathProbe, kNarrowProbeDirections rays,
// each counted at most kNarrowProbeCap piece sizes; the back of a sheet, a lamp's above a ceiling,
// counts as open: no light comes from it). A piece is in a narrow space when at least
// kNarrowNearShare of its rays meet a surface within its own size; it is then split again to
// about L / kNarrowDivisions, L their mean length: in a 10 cm crevice L is about 0.2 m, so 0.25 m
// pieces become 0.1 m ones. A room's pieces, corners included, keep their size (a room's corner
// sends most rays across the room). A gap so narrow that the split would go past kNarrowMaxSplit
// along an edge (a cabinet 1 cm from a wall) is left alone: its light dies within a few widths of
// its mouth, a band no such split resolves, and splitting would multiply the piece's patches.
// Splitting finer, or leaving more of the crevices to the narrow-gap rule, was measured worse for
// the patches it costs (docs/BENCHMARKS-accuracy.md).
// Deterministic like the probe: every machine that meshes the scene splits the same pieces.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "mesh/free_path_probe.h"
#include "mesh/polygon_split.h"

namespace radfarm {

inline constexpr int kNarrowProbeDirections = 8;
inline constexpr double kNarrowProbeCap = 4;
inline constexpr double kNarrowNearShare = 0.625;
inline constexpr double kNarrowDivisions = 2;
inline constexpr double kNarrowMaxSplit = 4;

// A piece of a face (its index in EmitPieces' order) that a narrow space splits again.
struct NarrowPiece {
  uint32_t piece = 0;
  double size = 0;  // the finer patch size it is split to
};

// The pieces of a face (split at `size`, with unit normal `normal`) that look into a narrow space.
std::vector<NarrowPiece> FindNarrowPieces(const FreePathProbe& probe,
                                          const std::vector<PieceCorners>& pieces,
                                          const Vec3& normal, double size, double tol);

// The number of pieces `narrow` adds to the face's.
uint64_t NarrowExtraPieces(const std::vector<PieceCorners>& pieces, const Vec3& normal,
                           const std::vector<NarrowPiece>& narrow, double tol);

// Replaces each narrow piece in `pieces` by its split, in place and in order.
void SplitNarrowPieces(const std::vector<NarrowPiece>& narrow, const Vec3& normal, double tol,
                       std::vector<PieceCorners>* pieces);

}  // namespace radfarm
