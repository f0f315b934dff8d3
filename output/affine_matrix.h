// Column-major 4x4 affine matrices as glTF writes them (InputObject::local/world): products,
// inverses and points, for putting world-space display vertices back into an object's own frame.
#pragma once

#include <array>
#include <optional>

#include "core/vec3.h"

namespace radfarm {

using AffineMatrix = std::array<double, 16>;  // m[4 * column + row]; last row 0 0 0 1

AffineMatrix Multiply(const AffineMatrix& a, const AffineMatrix& b);
Vec3 TransformPoint(const AffineMatrix& m, const Vec3& p);
// None when the upper-left 3x3 is singular or nearly so (a scale of 0 flattens the object).
std::optional<AffineMatrix> InvertAffine(const AffineMatrix& m);

}  // namespace radfarm
