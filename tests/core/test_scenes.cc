#include "tests/core/test_scenes.h"

#include <cmath>
#include <cstring>
#include <numbers>
#include <utility>

namespace radfarm::testing {
namespace {

Patch MakePatch(std::initializer_list<Vec3> corners, const Surface& s) {
  Patch p;
  p.corner_count = static_cast<uint8_t>(corners.size());
  int k = 0;
  for (const Vec3& c : corners) p.corners[k++] = c;
  const Vec3 n = Cross(p.corners[1] - p.corners[0], p.corners[2] - p.corners[0]);
  p.normal = Normalize(n);
  double area = Length(n) / 2;
  Vec3 centre = (p.corners[0] + p.corners[1] + p.corners[2]) / 3 * area;
  if (p.corner_count == 4) {
    const double a2 = Length(Cross(p.corners[2] - p.corners[0], p.corners[3] - p.corners[0])) / 2;
    centre += (p.corners[0] + p.corners[2] + p.corners[3]) / 3 * a2;
    area += a2;
  }
  p.area = area;
  p.centre = centre / area;
  p.reflectance = s.reflectance;
  p.emission = s.emission;
  p.surface = s.surface;
  return p;
}

Vec3 Bilinear(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double u, double v) {
  return a * ((1 - u) * (1 - v)) + b * (u * (1 - v)) + c * (u * v) + d * ((1 - u) * v);
}

}  // namespace

void AddQuadGrid(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int n,
                 const Surface& s, PatchScene* scene) {
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u0 = double(i) / n, u1 = double(i + 1) / n;
      const double v0 = double(j) / n, v1 = double(j + 1) / n;
      scene->patches.push_back(
          MakePatch({Bilinear(a, b, c, d, u0, v0), Bilinear(a, b, c, d, u1, v0),
                     Bilinear(a, b, c, d, u1, v1), Bilinear(a, b, c, d, u0, v1)},
                    s));
    }
  }
}

void AddDisc(const Vec3& centre, const Vec3& normal, double radius, int segments, const Surface& s,
             PatchScene* scene) {
  Vec3 t, b;
  OrthonormalBasis(normal, &t, &b);
  for (int k = 0; k < segments; ++k) {
    const double a0 = 2 * std::numbers::pi * k / segments;
    const double a1 = 2 * std::numbers::pi * (k + 1) / segments;
    const Vec3 p0 = centre + (t * std::cos(a0) + b * std::sin(a0)) * radius;
    const Vec3 p1 = centre + (t * std::cos(a1) + b * std::sin(a1)) * radius;
    scene->patches.push_back(MakePatch({centre, p0, p1}, s));
  }
}

PatchScene MakeClosedBox(const Vec3& lo, const Vec3& hi, int n, const Surface& s) {
  PatchScene scene;
  scene.material_names = {"box"};
  const Vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                     {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                     {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  const int faces[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                           {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  const Vec3 box_centre = (lo + hi) / 2;
  for (int f = 0; f < 6; ++f) {
    Surface fs = s;
    fs.surface = f;
    Vec3 q[4] = {c[faces[f][0]], c[faces[f][1]], c[faces[f][2]], c[faces[f][3]]};
    // Wind each face so that its normal points into the box.
    const Vec3 normal = Cross(q[1] - q[0], q[2] - q[0]);
    if (Dot(normal, box_centre - q[0]) < 0) std::swap(q[1], q[3]);
    AddQuadGrid(q[0], q[1], q[2], q[3], n, fs, &scene);
  }
  return scene;
}

PatchScene LitBox() {
  PatchScene scene = MakeClosedBox({0, 0, 0}, {1, 1, 1}, 4, Surface{{0.7, 0.5, 0.3}, {}, 0});
  scene.patches[3 * 16 + 5].emission = {10, 10, 10};
  return scene;
}

PatchScene LightsOverFloor(int count) {
  PatchScene scene;
  for (int i = 0; i < count; ++i) {
    const double x = 2.0 * i;
    AddQuadGrid({x, 0, 1}, {x, 1, 1}, {x + 1, 1, 1}, {x + 1, 0, 1}, 6,
                Surface{{}, {1, 1, 1}, uint32_t(10 + i)}, &scene);
  }
  AddQuadGrid({-2, -2, 0}, {30, -2, 0}, {30, 2, 0}, {-2, 2, 0}, 60, Surface{{0.5, 0.5, 0.5}, {}, 1},
              &scene);
  return scene;
}

PatchScene LightsAndLampOverFloor() {
  PatchScene scene = LightsOverFloor(2);
  PunctualLight lamp;
  lamp.kind = PunctualKind::kPoint;
  lamp.position = {5, 8, 5};
  lamp.direction = {0, -1, 0};
  lamp.intensity = {40, 30, 20};
  scene.lights.push_back(lamp);
  return scene;
}

bool BitIdentical(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  // memcmp of two empty vectors' null data pointers is undefined, even for 0 bytes.
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)) == 0);
}

SolverSettings Gathering(uint32_t gather_rays, uint64_t shot_rays) {
  SolverSettings s;
  s.shot_rays = shot_rays;
  s.gather_rays = gather_rays;
  s.threads = 2;
  return s;
}

}  // namespace radfarm::testing
