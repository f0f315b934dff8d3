// Pairs of triangles of a glTF model at the same place facing opposite ways: what a viewer drawing
// back faces z-fights on. For the tests of lit.glb (output/layer_separation.h), over every node's
// triangles in world space.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>
#include <vector>

namespace radfarm {

using WorldTriangle = std::array<std::array<double, 3>, 3>;

namespace coincident_detail {

using Matrix = std::array<double, 16>;  // column-major, as glTF

inline Matrix Times(const Matrix& a, const Matrix& b) {
  Matrix out{};
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      for (int k = 0; k < 4; ++k) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    }
  }
  return out;
}

inline void Collect(const tinygltf::Model& model, int node, const Matrix& parent,
                    std::vector<WorldTriangle>* out) {
  const tinygltf::Node& n = model.nodes[node];
  Matrix local = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (n.matrix.size() == 16) std::copy(n.matrix.begin(), n.matrix.end(), local.begin());
  const Matrix world = Times(parent, local);
  if (n.mesh >= 0) {
    for (const tinygltf::Primitive& p : model.meshes[n.mesh].primitives) {
      const auto read = [&](int index, size_t width, auto zero) {
        const tinygltf::Accessor& a = model.accessors[index];
        const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
        std::vector<decltype(zero)> values(a.count * width);
        std::memcpy(values.data(),
                    model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset,
                    values.size() * sizeof(zero));
        return values;
      };
      const std::vector<float> xyz = read(p.attributes.at("POSITION"), 3, 0.0f);
      const std::vector<uint32_t> corners = read(p.indices, 1, uint32_t{0});
      for (size_t t = 0; t + 2 < corners.size(); t += 3) {
        WorldTriangle tri;
        for (int c = 0; c < 3; ++c) {
          const float* q = &xyz[size_t{corners[t + c]} * 3];
          for (int r = 0; r < 3; ++r) {
            tri[c][r] = world[r] * q[0] + world[4 + r] * q[1] + world[8 + r] * q[2] + world[12 + r];
          }
        }
        out->push_back(tri);
      }
    }
  }
  for (int child : n.children) Collect(model, child, world, out);
}

inline std::array<double, 3> Normal(const WorldTriangle& t) {
  const auto d = [&](int a, int k) { return t[a][k] - t[0][k]; };
  return {d(1, 1) * d(2, 2) - d(1, 2) * d(2, 1), d(1, 2) * d(2, 0) - d(1, 0) * d(2, 2),
          d(1, 0) * d(2, 1) - d(1, 1) * d(2, 0)};
}

}  // namespace coincident_detail

// Every triangle of the model's scene, in world space.
inline std::vector<WorldTriangle> WorldTriangles(const tinygltf::Model& model) {
  std::vector<WorldTriangle> out;
  const coincident_detail::Matrix identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  for (int root : model.scenes.at(0).nodes) coincident_detail::Collect(model, root, identity, &out);
  return out;
}

// How many pairs of triangles have each corner within `tolerance` of a corner of the other and
// normals pointing opposite ways. Triangles are bucketed by centroid in cells of `tolerance`.
inline size_t CoincidentOppositePairs(const std::vector<WorldTriangle>& triangles,
                                      double tolerance) {
  using Cell = std::tuple<long, long, long>;
  const auto centroid = [](const WorldTriangle& t) {
    return std::array<double, 3>{(t[0][0] + t[1][0] + t[2][0]) / 3,
                                 (t[0][1] + t[1][1] + t[2][1]) / 3,
                                 (t[0][2] + t[1][2] + t[2][2]) / 3};
  };
  std::map<Cell, std::vector<size_t>> cells;
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto c = centroid(triangles[i]);
    cells[{std::lround(c[0] / tolerance), std::lround(c[1] / tolerance),
           std::lround(c[2] / tolerance)}]
        .push_back(i);
  }
  const auto near = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::abs(a[0] - b[0]) <= tolerance && std::abs(a[1] - b[1]) <= tolerance &&
           std::abs(a[2] - b[2]) <= tolerance;
  };
  size_t pairs = 0;
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto c = centroid(triangles[i]);
    const Cell home = {std::lround(c[0] / tolerance), std::lround(c[1] / tolerance),
                       std::lround(c[2] / tolerance)};
    for (long dx = -1; dx <= 1; ++dx) {
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it =
              cells.find({std::get<0>(home) + dx, std::get<1>(home) + dy, std::get<2>(home) + dz});
          if (it == cells.end()) continue;
          for (size_t j : it->second) {
            if (j <= i) continue;
            const WorldTriangle& a = triangles[i];
            const WorldTriangle& b = triangles[j];
            const bool same_place = std::all_of(a.begin(), a.end(), [&](const auto& p) {
              return std::any_of(b.begin(), b.end(), [&](const auto& q) { return near(p, q); });
            });
            const auto na = coincident_detail::Normal(a), nb = coincident_detail::Normal(b);
            const double dot = na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2];
            if (same_place && dot < 0) ++pairs;
          }
        }
      }
    }
  }
  return pairs;
}

}  // namespace radfarm
