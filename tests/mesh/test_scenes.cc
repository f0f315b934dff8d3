#include "test_scenes.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "display/display_stage.h"
#include "mesh/polygon.h"

namespace radfarm::testing {

SceneBuilder::SceneBuilder(std::string path) { scene_.path = std::move(path); }

uint32_t SceneBuilder::AddMaterial(const std::string& name, Rgb diffuse, Rgb emission) {
  scene_.materials.push_back({name, diffuse, emission});
  return static_cast<uint32_t>(scene_.materials.size() - 1);
}

uint32_t SceneBuilder::AddFace(const std::vector<Vec3>& corners, uint32_t material, uint32_t line) {
  InputFace face;
  for (const Vec3& p : corners) {
    face.indices.push_back(static_cast<uint32_t>(scene_.positions.size()));
    scene_.positions.push_back(p);
  }
  face.material = material;
  face.line = line != 0 ? line : static_cast<uint32_t>(scene_.faces.size() + 1);
  scene_.faces.push_back(face);
  return face.line;
}

void SceneBuilder::AddBox(const Vec3& lo, const Vec3& hi, uint32_t material, bool normals_in) {
  auto at = [&](int x, int y, int z) {
    return Vec3{x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z};
  };
  // Counter-clockwise seen from outside.
  const std::vector<std::vector<Vec3>> faces = {
      {at(0, 0, 0), at(1, 0, 0), at(1, 0, 1), at(0, 0, 1)},  // -y
      {at(0, 1, 0), at(0, 1, 1), at(1, 1, 1), at(1, 1, 0)},  // +y
      {at(0, 0, 0), at(0, 0, 1), at(0, 1, 1), at(0, 1, 0)},  // -x
      {at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1)},  // +x
      {at(0, 0, 0), at(0, 1, 0), at(1, 1, 0), at(1, 0, 0)},  // -z
      {at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1)},  // +z
  };
  for (std::vector<Vec3> f : faces) {
    if (normals_in) std::reverse(f.begin(), f.end());
    AddFace(f, material);
  }
}

InputScene SceneOf(const std::vector<std::vector<Vec3>>& faces) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  for (const auto& f : faces) b.AddFace(f);
  return b.scene();
}

InputScene CornellBox(bool with_block_bottoms) {
  SceneBuilder b("scenes/cornell-box.obj");
  const uint32_t white = b.AddMaterial("white", {0.725, 0.71, 0.68});
  const uint32_t red = b.AddMaterial("red", {0.63, 0.065, 0.05});
  const uint32_t green = b.AddMaterial("green", {0.14, 0.45, 0.091});
  const uint32_t light = b.AddMaterial("light", {0.78, 0.78, 0.78}, {17, 12, 4});
  b.AddFace({{552.8, 0, 0}, {0, 0, 0}, {0, 0, 559.2}, {549.6, 0, 559.2}}, white);
  b.AddFace({{556, 548.8, 0}, {556, 548.8, 559.2}, {0, 548.8, 559.2}, {0, 548.8, 0}}, white);
  b.AddFace({{549.6, 0, 559.2}, {0, 0, 559.2}, {0, 548.8, 559.2}, {556, 548.8, 559.2}}, white);
  b.AddFace({{0, 0, 559.2}, {0, 0, 0}, {0, 548.8, 0}, {0, 548.8, 559.2}}, green);
  b.AddFace({{552.8, 0, 0}, {549.6, 0, 559.2}, {556, 548.8, 559.2}, {556, 548.8, 0}}, red);
  b.AddFace({{343, 548, 227}, {343, 548, 332}, {213, 548, 332}, {213, 548, 227}}, light);
  const std::vector<std::vector<Vec3>> short_block = {
      {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}},
      {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}},
      {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}},
      {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}},
      {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}},
  };
  const std::vector<std::vector<Vec3>> tall_block = {
      {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}},
      {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}},
      {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}},
      {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}},
      {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}},
  };
  for (const auto* block : {&short_block, &tall_block}) {
    for (const auto& f : *block) b.AddFace(f, white);
    if (with_block_bottoms) {
      // The top, reversed and moved down to the floor: it faces down onto the floor.
      std::vector<Vec3> bottom = (*block)[0];
      std::reverse(bottom.begin(), bottom.end());
      for (Vec3& p : bottom) p.y = 0;
      b.AddFace(bottom, white);
    }
  }
  return b.scene();
}

InputScene OccluderScene() {
  SceneBuilder s;
  s.AddMaterial("white", {0.5, 0.5, 0.5});
  s.AddMaterial("light", {0, 0, 0}, {10, 10, 10});
  s.AddFace({{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}}, 0);
  s.AddFace({{1.6, 1, 1.6}, {2.4, 1, 1.6}, {2.4, 1, 2.4}, {1.6, 1, 2.4}}, 0);
  s.AddFace({{1.9, 2, 1.9}, {2.1, 2, 1.9}, {2.1, 2, 2.1}, {1.9, 2, 2.1}}, 1);
  return s.scene();
}

double TotalArea(const PatchScene& scene) {
  double sum = 0;
  for (const Patch& p : scene.patches) sum += p.area;
  return sum;
}

double LongestEdge(const Patch& patch) {
  double longest = 0;
  for (int i = 0; i < patch.corner_count; ++i) {
    const Vec3 edge = patch.corners[(i + 1) % patch.corner_count] - patch.corners[i];
    longest = std::max(longest, Length(edge));
  }
  return longest;
}

namespace {

// Barycentric coordinates of p's projection onto triangle t's plane.
void Barycentric(const DisplayMesh& mesh, size_t t, const Vec3& p, double w[3], double* height) {
  const auto& tri = mesh.triangles[t];
  const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
  const Vec3 n = Cross(b - a, c - a);
  const double n2 = Dot(n, n);
  w[0] = Dot(Cross(c - b, p - b), n) / n2;
  w[1] = Dot(Cross(a - c, p - c), n) / n2;
  w[2] = 1 - w[0] - w[1];
  *height = std::fabs(Dot(p - a, n)) / std::sqrt(n2);
}

}  // namespace

Rgb Interpolate(const DisplayMesh& mesh, size_t t, const Vec3& p) {
  double w[3], height;
  Barycentric(mesh, t, p, w, &height);
  const auto& tri = mesh.triangles[t];
  return mesh.radiance[tri[0]] * w[0] + mesh.radiance[tri[1]] * w[1] + mesh.radiance[tri[2]] * w[2];
}

bool Contains(const DisplayMesh& mesh, size_t t, const Vec3& p, double tol) {
  double w[3], height;
  Barycentric(mesh, t, p, w, &height);
  return height <= tol && w[0] >= -tol && w[1] >= -tol && w[2] >= -tol;
}

std::vector<std::string> FindCracks(const DisplayMesh& mesh, const PatchScene& scene) {
  std::vector<uint32_t> vertex_surface(mesh.positions.size(), 0xffffffffu);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint32_t v : mesh.triangles[t]) {
      vertex_surface[v] = scene.patches[mesh.triangle_patch[t]].surface;
    }
  }
  std::vector<std::string> cracks;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const uint32_t surface = scene.patches[mesh.triangle_patch[t]].surface;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = mesh.positions[mesh.triangles[t][k]];
      const Vec3 c = mesh.positions[mesh.triangles[t][(k + 1) % 3]];
      for (uint32_t v = 0; v < mesh.positions.size(); ++v) {
        if (vertex_surface[v] != surface) continue;
        const Vec3 p = mesh.positions[v];
        const double along = Dot(p - a, c - a) / Dot(c - a, c - a);
        if (along <= 1e-9 || along >= 1 - 1e-9) continue;
        if (Length(p - (a + (c - a) * along)) <= 1e-9) {
          cracks.push_back("vertex " + std::to_string(v) + " lies inside an edge of triangle " +
                           std::to_string(t));
        }
      }
    }
  }
  return cracks;
}

DisplayMesh AveragedOf(const PatchMesh& mesh, std::vector<Rgb> values) {
  if (values.empty()) values.resize(mesh.patch_scene().patches.size());
  return AveragedDisplay(mesh.display_topology(), mesh.patch_scene(), values);
}

}  // namespace radfarm::testing
