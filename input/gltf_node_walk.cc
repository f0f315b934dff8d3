#include "input/gltf_node_walk.h"

#include <cmath>
#include <vector>

namespace radfarm {
namespace {

constexpr int kMaxDepth = 1024;  // deeper hierarchies are cycles or hostile files

Mat4 Translation(const std::vector<double>& t) {
  Mat4 out;
  out.m[12] = t[0];
  out.m[13] = t[1];
  out.m[14] = t[2];
  return out;
}

// A unit quaternion (x, y, z, w) as a rotation matrix; glTF requires unit quaternions, and
// normalising here forgives the rounding of exporters.
Mat4 Rotation(const std::vector<double>& q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
  Mat4 out;
  out.m = {1 - 2 * (y * y + z * z),
           2 * (x * y + z * w),
           2 * (x * z - y * w),
           0,
           2 * (x * y - z * w),
           1 - 2 * (x * x + z * z),
           2 * (y * z + x * w),
           0,
           2 * (x * z + y * w),
           2 * (y * z - x * w),
           1 - 2 * (x * x + y * y),
           0,
           0,
           0,
           0,
           1};
  return out;
}

Mat4 Scale(const std::vector<double>& s) {
  Mat4 out;
  out.m[0] = s[0];
  out.m[5] = s[1];
  out.m[10] = s[2];
  return out;
}

bool AllFinite(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

struct WalkState {
  std::vector<bool> on_path;
  int visits = 0;
};

Status Walk(const tinygltf::Model& model, int node, const Mat4& parent, int parent_visit,
            WalkState* state, int depth,
            const std::function<Status(int, const Mat4&, int)>& visit) {
  if (node < 0 || static_cast<size_t>(node) >= model.nodes.size()) {
    return Error{"node " + std::to_string(node) + " does not exist"};
  }
  const std::string what = NodeName(model, node);
  if (state->on_path[node] || depth > kMaxDepth) return Error{what + ": is its own ancestor"};
  const tinygltf::Node& n = model.nodes[node];
  Result<Mat4> local = LocalMatrix(n, what);
  RADFARM_RETURN_IF_ERROR(local);
  const Mat4 world = parent * *local;
  const int this_visit = state->visits++;
  RADFARM_RETURN_IF_ERROR(visit(node, world, parent_visit));
  state->on_path[node] = true;
  for (int child : n.children) {
    RADFARM_RETURN_IF_ERROR(Walk(model, child, world, this_visit, state, depth + 1, visit));
  }
  state->on_path[node] = false;
  return Ok{};
}

}  // namespace

double Mat4::Determinant() const {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
         m[8] * (m[1] * m[6] - m[5] * m[2]);
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 out;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a.m[4 * k + r] * b.m[4 * c + k];
      out.m[4 * c + r] = sum;
    }
  }
  return out;
}

std::string NodeName(const tinygltf::Model& model, int node) {
  std::string out = "node " + std::to_string(node);
  if (node >= 0 && static_cast<size_t>(node) < model.nodes.size() &&
      !model.nodes[node].name.empty()) {
    out += " '" + model.nodes[node].name + "'";
  }
  return out;
}

Result<Mat4> LocalMatrix(const tinygltf::Node& node, const std::string& what) {
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16 || !AllFinite(node.matrix)) {
      return Error{what + ": matrix must be 16 finite numbers"};
    }
    Mat4 out;
    for (int i = 0; i < 16; ++i) out.m[i] = node.matrix[i];
    if (out.m[3] != 0 || out.m[7] != 0 || out.m[11] != 0 || out.m[15] != 1) {
      return Error{what + ": matrix is not affine (its last row must be 0 0 0 1)"};
    }
    return out;
  }
  Mat4 out;
  if (!node.translation.empty()) {
    if (node.translation.size() != 3 || !AllFinite(node.translation)) {
      return Error{what + ": translation must be 3 finite numbers"};
    }
    out = Translation(node.translation);
  }
  if (!node.rotation.empty()) {
    const std::vector<double>& q = node.rotation;
    if (q.size() != 4 || !AllFinite(q) ||
        q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] == 0) {
      return Error{what + ": rotation must be a quaternion of 4 finite numbers, not all 0"};
    }
    out = out * Rotation(q);
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3 || !AllFinite(node.scale)) {
      return Error{what + ": scale must be 3 finite numbers"};
    }
    out = out * Scale(node.scale);
  }
  return out;
}

Status WalkScene(const tinygltf::Model& model, const tinygltf::Scene& scene,
                 const std::function<Status(int, const Mat4&)>& visit) {
  return WalkSceneTree(model, scene,
                       [&](int node, const Mat4& world, int) { return visit(node, world); });
}

Status WalkSceneTree(const tinygltf::Model& model, const tinygltf::Scene& scene,
                     const std::function<Status(int, const Mat4&, int)>& visit) {
  WalkState state;
  state.on_path.resize(model.nodes.size());
  for (int root : scene.nodes) {
    RADFARM_RETURN_IF_ERROR(Walk(model, root, Mat4{}, -1, &state, 0, visit));
  }
  return Ok{};
}

}  // namespace radfarm
