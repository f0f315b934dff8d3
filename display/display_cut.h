// When the display cuts a triangle where the light bends (display/light_bends.h): the contrast
// between its corners' light above which it is cut into four.
#pragma once

#include "core/vec3.h"

namespace radfarm {

// Where a display triangle's corners differ by more than this share of the brightest, the light
// bends within it faster than the display shows: the ceiling just outside a hanging lamp's outline
// rises from the slit's shadow within centimetres, a hard shadow's edge crosses it.
inline constexpr double kRefineContrast = 0.2;

// The cuts leave slivers beside them (a triangle with one cut edge is halved, selective_split.h),
// some reaching from a leg's foot 10 cm out across where the light recovers beside it: such a
// triangle's corners show the light along its long edges only, so between gathered corners it is
// cut at half the contrast: the walls' junctions then show their light for a few more points
// (docs/BENCHMARKS-accuracy.md).
inline constexpr double kSliverQuality = 0.3;  // TriangleQuality below this is a sliver
inline constexpr double kSliverContrast = 0.1;

// 1 for an equilateral triangle, falling to 0 as it flattens: 4 sqrt(3) area over the sum of the
// squared edges.
double TriangleQuality(const Vec3& a, const Vec3& b, const Vec3& c);

// The contrast above which the triangle (a, b, c) is cut: kSliverContrast for a sliver whose
// corners all gathered their own light, kRefineContrast otherwise (the direct light's contrast,
// at a shadow's edge, is sharp at any shape).
double CutContrast(const Vec3& a, const Vec3& b, const Vec3& c, bool gathered);

}  // namespace radfarm
