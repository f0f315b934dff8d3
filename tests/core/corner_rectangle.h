// The form factor from a point to a parallel rectangle a x b at height 1 with a corner straight
// above it: 1/(2 pi) [A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))];
// signed (negative when exactly one of a, b is), so rectangles off the point add and subtract.
// Header-only: the core and mesh test binaries both check against it.
#pragma once

#include <cmath>
#include <numbers>

namespace radfarm::testing {

inline double CornerRectangle(double a, double b) {
  const double fa = std::abs(a), fb = std::abs(b);
  const double f = (fa / std::sqrt(1 + fa * fa) * std::atan(fb / std::sqrt(1 + fa * fa)) +
                    fb / std::sqrt(1 + fb * fb) * std::atan(fa / std::sqrt(1 + fb * fb))) /
                   (2 * std::numbers::pi);
  return (a < 0) != (b < 0) ? -f : f;
}

}  // namespace radfarm::testing
