// Hand-built PatchScenes for core tests, independent of the OBJ loader and the mesher.
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/solver_settings.h"
#include "tests/core/corner_rectangle.h"  // CornerRectangle, for the tests that use these scenes

namespace radfarm::testing {

struct Surface {
  Rgb reflectance;
  Rgb emission;
  uint32_t surface = 0;
};

// Appends the quad a,b,c,d (counter-clockwise seen from its front) as an n x n grid of patches.
void AddQuadGrid(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int n,
                 const Surface& s, PatchScene* scene);

// Appends a regular polygon approximating a disc (centre, unit normal, radius) as a fan of
// triangles around the centre.
void AddDisc(const Vec3& centre, const Vec3& normal, double radius, int segments, const Surface& s,
             PatchScene* scene);

// A closed axis-aligned box [lo, hi] with faces facing inward, each split n x n; all faces get s
// (surface ids 0..5 in the order -x, +x, -y, +y, -z, +z).
PatchScene MakeClosedBox(const Vec3& lo, const Vec3& hi, int n, const Surface& s);

// MakeClosedBox of the unit cube, 4 x 4 patches a face, reflectance (0.7, 0.5, 0.3), one patch of
// the +y face (the ceiling) emitting 10.
PatchScene LitBox();

// `count` lights of 36 patches each (distinct surfaces 10, 11, ...) over a grey 60 x 60 floor: up
// to 8 keep the direct-light start at 2048 gather rays (core/direct_light.h).
PatchScene LightsOverFloor(int count);

// LightsOverFloor(2) and a point lamp over the floor: emitter patches and a punctual light both in
// a direct-light start.
PatchScene LightsAndLampOverFloor();

// Whether two solutions are the same to the bit.
bool BitIdentical(const std::vector<Rgb>& a, const std::vector<Rgb>& b);

// Patch index range helper: patches [first, last) of a scene.
struct PatchRange {
  uint32_t first = 0, last = 0;
};

// Settings of a solve with the final gather: `gather_rays` per patch, `shot_rays` (0: automatic),
// 2 threads.
SolverSettings Gathering(uint32_t gather_rays, uint64_t shot_rays = 0);

}  // namespace radfarm::testing
