// glTF node transforms: each node's local matrix (its `matrix`, or translation * rotation * scale),
// and a walk over a scene's node hierarchy that hands every node its world matrix.
#pragma once

#include <tiny_gltf.h>

#include <array>
#include <functional>
#include <string>

#include "base/result.h"
#include "core/vec3.h"

namespace radfarm {

// A 4x4 affine matrix, column-major as glTF writes it: m[4 * column + row].
struct Mat4 {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

  Vec3 Point(const Vec3& p) const {
    return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
            m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
            m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
  }
  Vec3 Direction(const Vec3& d) const {
    return {m[0] * d.x + m[4] * d.y + m[8] * d.z, m[1] * d.x + m[5] * d.y + m[9] * d.z,
            m[2] * d.x + m[6] * d.y + m[10] * d.z};
  }
  // Of the upper-left 3x3: negative when the transform mirrors, which flips triangle winding.
  double Determinant() const;
};

Mat4 operator*(const Mat4& a, const Mat4& b);

// The node's local transform. Errors name the node: non-finite values, a matrix that is not affine.
Result<Mat4> LocalMatrix(const tinygltf::Node& node, const std::string& what);

// "node 3 'Lamp'".
std::string NodeName(const tinygltf::Model& model, int node);

// Calls visit(node index, world matrix) for every node of the scene, parents before children, in
// the file's order. Errors: a node index out of range, a node that is its own ancestor, a bad
// transform, or visit's own error.
Status WalkScene(const tinygltf::Model& model, const tinygltf::Scene& scene,
                 const std::function<Status(int, const Mat4&)>& visit);

// As WalkScene, and visit also gets the number of its parent's visit (visits numbered from 0 in
// the order they are made; -1 for a root), so a caller can rebuild the tree it walked.
Status WalkSceneTree(const tinygltf::Model& model, const tinygltf::Scene& scene,
                     const std::function<Status(int, const Mat4&, int)>& visit);

}  // namespace radfarm
