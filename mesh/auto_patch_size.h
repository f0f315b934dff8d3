// The automatic patch size (MeshSettings::patch_size == 0), chosen per face from the space the
// face looks into, so a room is meshed alike in a building of 4 rooms or of 400.
//
// Light reaching a face comes from the surfaces it sees, and varies across it on the scale of
// their distance: a face's radiosity bends over about its mean free path L, the mean length of
// cosine-distributed rays from the face to the first surface they meet (in a closed convex room
// the mean chord, 4 V / S: 2.4 m for a 4 x 4 x 3 m room). The face's target size is L /
// kAutoChordDivisions. L is measured with the Embree caster on a probe mesh (each face one or a
// few pieces): kAutoProbeDirections rays from each of up to kAutoProbePoints points of the face;
// a ray that leaves the scene counts as the scene's diagonal. A face in a narrow gap (a
// cabinet's back against a wall) is cut no finer than its bounding box's diagonal /
// kAutoMaxFaceDivisions. Sizes are rounded down to a ladder of kAutoSizeSteps per octave, so faces
// in alike rooms get the same size despite rounding in the rays. Deterministic: fixed directions,
// each face's rays summed in one order whatever thread probes it.
#pragma once

#include <vector>

#include "core/thread_pool.h"
#include "mesh/clean_faces.h"
#include "mesh/free_path_probe.h"

namespace radfarm {

inline constexpr double kAutoChordDivisions = 10;
inline constexpr int kAutoProbeDirections = 16;
inline constexpr size_t kAutoProbePoints = 9;
inline constexpr double kAutoMaxFaceDivisions = 32;
inline constexpr double kAutoSizeSteps = 8;

// Per face, its mean free path L (see above), measured on `probe`, a probe of these faces (the one
// the mesher keeps for narrow spaces too); a miss counts as the probe's diagonal. The faces are
// spread over `pool` when given.
std::vector<double> MeanFreePaths(const std::vector<CleanFace>& faces, const FreePathProbe& probe,
                                  double tol, ThreadPool* pool = nullptr);

// Per face, its automatic target patch size from its mean free path.
std::vector<double> AutoPatchSizes(const std::vector<CleanFace>& faces, const FreePathProbe& probe,
                                   double tol, ThreadPool* pool = nullptr);

// The largest ladder size 2^(i / kAutoSizeSteps) (integer i) not above `size` (> 0).
double LadderSize(double size);

}  // namespace radfarm
