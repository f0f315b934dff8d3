// The automatic camera of every shipped closed scene, judged from its picture: the eye stands
// inside the room, clear of geometry, and the frame shows the room (several surfaces, none filling
// it alone, no black outside) rather than one wall in a black frame. Each scene is loaded and
// meshed as `render` does, its display triangles coloured by surface and drawn by the real
// rasteriser with the camera `render` would choose (output/enclosure_camera.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli/job_inputs.h"
#include "display/patch_triangles.h"
#include "output/enclosure_camera.h"
#include "output/image.h"

namespace radfarm {
namespace {

// The least distance from p to the triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double PointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return Length(p - a);
  const Vec3 bp = p - b;
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return Length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return Length(p - (a + ab * (d1 / (d1 - d3))));
  const Vec3 cp = p - c;
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return Length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return Length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    return Length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  }
  const double denom = 1 / (va + vb + vc);
  return Length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

// The display triangles of a shipped scene, coloured by surface (1, 2, ...; a display vertex
// belongs to one surface), and its job.
struct Shown {
  Job job;
  DisplayMesh mesh;
};

Shown Load(const std::string& scene) {
  std::vector<std::string> warnings;
  Result<LoadedJob> loaded =
      LoadJobForSolve(std::string(RADFARM_SOURCE_DIR "/scenes/") + scene, {}, &warnings);
  EXPECT_TRUE(loaded.ok()) << loaded.error();
  if (!loaded.ok()) return {};
  const PatchScene& patches = loaded->mesh.patch_scene();
  Shown out{loaded->job, PatchTriangles(loaded->mesh.display_topology(), patches, {})};
  out.mesh.radiance.assign(out.mesh.positions.size(), Rgb());
  for (size_t t = 0; t < out.mesh.triangles.size(); ++t) {
    const double id = patches.patches[out.mesh.triangle_patch[t]].surface + 1;
    for (uint32_t v : out.mesh.triangles[t]) out.mesh.radiance[v] = Rgb(id, 0, 0);
  }
  return out;
}

// Of rays from `eye` in 50 fixed directions, the share whose nearest triangle shows its front
// (a two-sided layer facing away is not there for the ray): inside a room nearly all, inside a
// solid block or outside a room few.
double FrontShare(const DisplayMesh& mesh, const Vec3& eye) {
  uint64_t state = 12345;
  const auto uniform = [&] {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  int front = 0;
  constexpr int kRays = 50;
  for (int r = 0; r < kRays; ++r) {
    const double z = 2 * uniform() - 1, phi = 2 * M_PI * uniform();
    const Vec3 dir = {std::sqrt(1 - z * z) * std::cos(phi), z,
                      std::sqrt(1 - z * z) * std::sin(phi)};
    double nearest = INFINITY;
    bool faces = false;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Vec3 &a = mesh.positions[mesh.triangles[t][0]],
                 &b = mesh.positions[mesh.triangles[t][1]],
                 &c = mesh.positions[mesh.triangles[t][2]];
      const Vec3 n = Cross(b - a, c - a);
      const uint32_t patch = mesh.triangle_patch[t];
      const bool front_only = patch < mesh.patch_front_only.size() && mesh.patch_front_only[patch];
      if (front_only && Dot(n, dir) >= 0) continue;
      const Vec3 e1 = b - a, e2 = c - a, p = Cross(dir, e2);
      const double det = Dot(e1, p);
      if (det == 0) continue;
      const Vec3 s = eye - a;
      const double u = Dot(s, p) / det;
      const Vec3 q = Cross(s, e1);
      const double v = Dot(dir, q) / det, dist = Dot(e2, q) / det;
      if (u < 0 || v < 0 || u + v > 1 || dist <= 0 || dist >= nearest) continue;
      nearest = dist;
      faces = Dot(n, dir) < 0;
    }
    front += faces;
  }
  return static_cast<double>(front) / kRays;
}

class EnclosureViewTest : public ::testing::TestWithParam<const char*> {};

TEST_P(EnclosureViewTest, TheAutomaticCameraShowsTheRoomFromInside) {
  Shown shown = Load(GetParam());
  ASSERT_TRUE(shown.job.camera.automatic);
  const DisplayMesh& mesh = shown.mesh;
  Camera wanted = shown.job.camera;
  wanted.width = wanted.height = 96;
  wanted.samples_per_pixel = 1;
  const Camera camera = ResolveCamera(mesh, wanted);

  const Bounds3 bounds = MeshBounds(mesh);
  const Vec3 extent = bounds.hi - bounds.lo;
  double nearest = INFINITY;
  for (const auto& tri : mesh.triangles) {
    nearest =
        std::min(nearest, PointTriangleDistance(camera.eye, mesh.positions[tri[0]],
                                                mesh.positions[tri[1]], mesh.positions[tri[2]]));
  }
  EXPECT_GE(nearest, 0.05 * std::min({extent.x, extent.y, extent.z}))
      << "eye " << camera.eye.x << " " << camera.eye.y << " " << camera.eye.z;
  EXPECT_GE(FrontShare(mesh, camera.eye), 0.9)
      << "eye " << camera.eye.x << " " << camera.eye.y << " " << camera.eye.z;

  const Image image = RenderImage(mesh, camera);
  std::map<long, size_t> pixels;  // by surface id, 0 for none
  for (const Rgb& p : image.pixels) ++pixels[std::lround(p.r)];
  const double total = static_cast<double>(image.pixels.size());
  size_t seen = 0, largest = 0;
  for (const auto& [id, count] : pixels) {
    if (id == 0) continue;
    if (count >= 0.01 * total) ++seen;
    largest = std::max(largest, count);
  }
  EXPECT_LE(pixels[0], 0.01 * total) << "pixels showing nothing";
  EXPECT_GE(seen, 4u) << "surfaces each on 1% of the frame";
  EXPECT_LE(largest, 0.6 * total) << "the largest surface's pixels";
}

class OpenSceneViewTest : public ::testing::TestWithParam<const char*> {};

// An open scene keeps the outside camera (AutoCamera): no place in it is enclosed.
TEST_P(OpenSceneViewTest, HasNoInsideCamera) {
  const Shown shown = Load(GetParam());
  const std::optional<Camera> inside =
      InsideCamera(shown.mesh, MeshBounds(shown.mesh), shown.job.camera);
  EXPECT_FALSE(inside.has_value())
      << "eye " << inside->eye.x << " " << inside->eye.y << " " << inside->eye.z;
}

INSTANTIATE_TEST_SUITE_P(ShippedOpenScenes, OpenSceneViewTest,
                         ::testing::Values("cornell-box.obj", "cornell-box-far.obj",
                                           "hard-shadow.obj", "tiny-receiver.obj"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           std::replace_if(
                               name.begin(), name.end(), [](char c) { return !std::isalnum(c); },
                               '_');
                           return name;
                         });

// Every shipped input that is a closed room and leaves the camera automatic.
INSTANTIATE_TEST_SUITE_P(
    ShippedClosedScenes, EnclosureViewTest,
    ::testing::Values("block-on-floor.toml", "block-on-floor-shared.toml", "desk-on-floor.toml",
                      "desk-on-floor-shared.toml", "lamp-under-ceiling.toml",
                      "lamp-under-ceiling.obj", "seed-room.obj", "furnace.obj", "high-albedo.obj",
                      "cornell-box-closed.obj", "block-on-floor.obj", "block-on-floor-shared.obj",
                      "desk-on-floor.obj", "desk-on-floor-shared.obj", "touching-boxes.obj"),
    [](const ::testing::TestParamInfo<const char*>& info) {
      std::string name = info.param;
      std::replace_if(
          name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
      return name;
    });

}  // namespace
}  // namespace radfarm
