// Closed scenes whose surfaces meet at T-junctions leak no rays: walls on floors, door sills
// beside room floors, legs under table tops, boxes on tables. Rays leave every patch from points
// all over it (near its edges too) in cosine-distributed directions, through RayCaster as the
// solver casts them; not one may miss the scene.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "core/ray_caster.h"
#include "input/input_scene.h"
#include "mesh/patch_mesh.h"
#include "scenegen/building.h"
#include "scenegen/obj_writer.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

// Radical inverse in base 2 (van der Corput): a stratified sequence in [0, 1).
double RadicalInverse(uint32_t i) {
  uint32_t bits = i;
  bits = (bits << 16) | (bits >> 16);
  bits = ((bits & 0x55555555u) << 1) | ((bits & 0xAAAAAAAAu) >> 1);
  bits = ((bits & 0x33333333u) << 2) | ((bits & 0xCCCCCCCCu) >> 2);
  bits = ((bits & 0x0F0F0F0Fu) << 4) | ((bits & 0xF0F0F0F0u) >> 4);
  bits = ((bits & 0x00FF00FFu) << 8) | ((bits & 0xFF00FF00u) >> 8);
  return bits * 0x1.0p-32;
}

double Fract(double x) { return x - std::floor(x); }

// A point of the patch at (u, v) in [0, 1)^2: a triangle by the square-root map, a quad as two
// triangles of the same area.
Vec3 PointOn(const Patch& p, double u, double v) {
  Vec3 a = p.corners[0], b = p.corners[1], c = p.corners[2];
  if (p.corner_count == 4) {
    const double first = Length(Cross(b - a, c - a));
    const double second = Length(Cross(c - a, p.corners[3] - a));
    const double split = first / (first + second);
    if (u < split) {
      u /= split;
    } else {
      u = (u - split) / (1 - split);
      b = c;
      c = p.corners[3];
    }
  }
  const double s = std::sqrt(u);
  return a * (1 - s) + b * (s * (1 - v)) + c * (s * v);
}

struct Escapes {
  uint64_t rays = 0;
  uint64_t escaped = 0;
  std::string first;  // the first few, for the failure message
};

// `rays_per_patch` rays from every patch of the scene meshed at `patch_size`.
Escapes CastFromEveryPatch(const std::string& obj, double patch_size, uint32_t rays_per_patch) {
  Escapes out;
  Result<InputScene> input = LoadObjScene(obj);
  EXPECT_TRUE(input.ok()) << input.error();
  if (!input.ok()) return out;
  MeshSettings settings;
  settings.patch_size = patch_size;
  Result<PatchMesh> mesh = PatchMesh::Build(*input, settings, nullptr);
  EXPECT_TRUE(mesh.ok()) << mesh.error();
  if (!mesh.ok()) return out;
  const PatchScene& scene = mesh->patch_scene();
  const RayCaster caster(scene);
  std::ostringstream first;
  first.precision(17);
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    Vec3 t, b;
    OrthonormalBasis(p.normal, &t, &b);
    for (uint32_t k = 0; k < rays_per_patch; ++k) {
      // Points by a rank-1 lattice, directions by the radical inverse: a different offset per
      // patch so the patches together cover the scene's directions densely.
      const double u = (k + 0.5) / rays_per_patch, v = Fract(k * 0.6180339887498949);
      const double r = std::sqrt(RadicalInverse(k + 1)), phi = 2 * M_PI * Fract(u * 7 + i * 0.7548);
      const Vec3 dir = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                       p.normal * std::sqrt(std::max(0.0, 1 - r * r));
      const Vec3 origin = PointOn(p, u, v);
      ++out.rays;
      if (caster.Trace(origin, dir, p.normal).patch != RayHit::kMiss) continue;
      if (++out.escaped <= 5) {
        first << "\n  patch " << i << " (" << scene.material_names[p.material] << ") from ("
              << origin.x << ", " << origin.y << ", " << origin.z << ") along (" << dir.x << ", "
              << dir.y << ", " << dir.z << ")";
      }
    }
  }
  out.first = first.str();
  return out;
}

void ExpectNoEscapes(const std::string& obj, double patch_size, uint32_t rays_per_patch) {
  const Escapes e = CastFromEveryPatch(obj, patch_size, rays_per_patch);
  EXPECT_GT(e.rays, 100000u);
  EXPECT_EQ(e.escaped, 0u) << e.escaped << " of " << e.rays << " rays escaped:" << e.first;
}

std::string WriteBuilding(const testing::TempDir& dir, const scenegen::BuildingParams& params) {
  Result<scenegen::SceneModel> model = scenegen::GenerateBuilding(params);
  EXPECT_TRUE(model.ok()) << model.error();
  scenegen::JobFileSettings job;
  job.eye = {1, 1.6, 1};
  job.target = {3, 1, 3};
  const Result<std::string> written = scenegen::WriteScene(*model, dir.path(), "b", job);
  EXPECT_TRUE(written.ok()) << written.error();
  return dir.File("b.obj");
}

TEST(Watertight, GeneratedBuildingLeaksNoRays) {
  testing::TempDir dir;
  const std::string obj =
      WriteBuilding(dir, {.floors = 1, .rooms_x = 2, .rooms_z = 2, .seed = 3, .windows = true});
  ExpectNoEscapes(obj, 0.25, 64);
}

// Another patch size and odd room sizes: the floor's, walls' and furniture's splits all differ.
TEST(Watertight, GeneratedBuildingAtAnotherPatchSizeLeaksNoRays) {
  testing::TempDir dir;
  const std::string obj = WriteBuilding(
      dir,
      {.floors = 2, .rooms_x = 2, .rooms_z = 1, .room_width = 3.7, .room_depth = 4.3, .seed = 9});
  ExpectNoEscapes(obj, 0.37, 64);
}

// A hand-made closed room: the floor is one face, the +x wall two faces side by side (a T-vertex
// on the floor's edge), a table (top on four legs) with a box on it, so walls meet the floor and
// the box meets the table top at T-junctions.
constexpr char kRoomObj[] = R"(mtllib room.mtl
usemtl white
v 0 0 0
v 3 0 0
v 3 0 2
v 0 0 2
v 0 2.5 0
v 3 2.5 0
v 3 2.5 2
v 0 2.5 2
v 3 0 1.3
v 3 2.5 1.3
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 9 10 6
f 9 3 7 10
usemtl light
v 1.2 2.49 0.7
v 1.8 2.49 0.7
v 1.8 2.49 1.3
v 1.2 2.49 1.3
f 11 12 13 14
usemtl white
v 1 0.7 0.5
v 2.1 0.7 0.5
v 2.1 0.7 1.2
v 1 0.7 1.2
v 1 0.74 0.5
v 2.1 0.74 0.5
v 2.1 0.74 1.2
v 1 0.74 1.2
f 15 16 17 18
f 19 22 21 20
f 15 19 20 16
f 16 20 21 17
f 17 21 22 18
f 18 22 19 15
)";

// A box of corners lo..hi without its bottom, as OBJ lines from vertex number `base`.
std::string BoxLines(const Vec3& lo, const Vec3& hi, int base, bool top = true) {
  std::ostringstream o;
  o.precision(17);
  for (int k = 0; k < 8; ++k) {
    o << "v " << ((k & 1) ? hi.x : lo.x) << " " << ((k & 2) ? hi.y : lo.y) << " "
      << ((k & 4) ? hi.z : lo.z) << "\n";
  }
  auto f = [&](int a, int b, int c, int d) {
    o << "f " << base + a << " " << base + b << " " << base + c << " " << base + d << "\n";
  };
  f(0, 4, 6, 2);  // -x
  f(1, 3, 7, 5);  // +x
  f(0, 2, 3, 1);  // -z
  f(4, 5, 7, 6);  // +z
  if (top) f(2, 6, 7, 3);
  return o.str();
}

TEST(Watertight, TableAndBoxOnAFloorAtTJunctionsLeakNoRays) {
  testing::TempDir dir;
  std::ofstream(dir.File("room.mtl")) << "newmtl white\nKd 0.7 0.7 0.7\n"
                                         "newmtl light\nKd 0.5 0.5 0.5\nKe 10 10 10\n";
  std::string obj = kRoomObj;
  int base = 23;
  for (double x : {1.03, 2.02}) {
    for (double z : {0.53, 1.12}) {
      obj += BoxLines({x, 0, z}, {x + 0.05, 0.7, z + 0.05}, base, false);
      base += 8;
    }
  }
  obj += BoxLines({1.3, 0.74, 0.6}, {1.61, 0.95, 0.93}, base);
  std::ofstream(dir.File("room.obj")) << obj;
  ExpectNoEscapes(dir.File("room.obj"), 0.17, 256);
}

// The layout of the office floors that leaked: one floor and one ceiling for the whole
// storey, an inner wall of solids standing on the floor up to the ceiling, a door in it with a
// lintel between the wall's two parts. On the ceiling the parts' and the lintel's sides meet at the
// door's edges; footprints were found on the floor but not on the ceiling, so the ceiling inside
// the wall shot its rays through the hole cut in the floor under it.
TEST(Watertight, WallOfSolidsOnAStoreySlabLeaksNoRays) {
  scenegen::SceneModel m;
  const uint32_t white = m.AddMaterial({"white", {0.7, 0.7, 0.7}, {}});
  const uint32_t light = m.AddMaterial({"light", {0.8, 0.8, 0.8}, {10, 10, 10}});
  const double w = 8.2, d = 6, h = 3, x0 = 4, x1 = 4.2, lintel = 2.1;
  m.AddRectangle({0, 0, 0}, {w, 0, d}, 1, true, white);
  m.AddRectangle({0, h, 0}, {w, h, d}, 1, false, white);
  m.AddRectangle({0, 0, 0}, {0, h, d}, 0, true, white);
  m.AddRectangle({w, 0, 0}, {w, h, d}, 0, false, white);
  m.AddRectangle({0, 0, 0}, {w, h, 0}, 2, true, white);
  m.AddRectangle({0, 0, d}, {w, h, d}, 2, false, white);
  // Three parts of the wall between two doors, z in [0, 1.5], [2.4, 3.6] and [4.5, 6]: the middle
  // part has both ends, so its footprint closes on the floor.
  const double part[3][2] = {{0, 1.5}, {2.4, 3.6}, {4.5, d}};
  for (int k = 0; k < 3; ++k) {
    const double z0 = part[k][0], z1 = part[k][1];
    m.AddRectangle({x0, 0, z0}, {x0, h, z1}, 0, false, white);
    m.AddRectangle({x1, 0, z0}, {x1, h, z1}, 0, true, white);
    if (k > 0) m.AddRectangle({x0, 0, z0}, {x1, h, z0}, 2, false, white);
    if (k < 2) m.AddRectangle({x0, 0, z1}, {x1, h, z1}, 2, true, white);
    if (k == 2) continue;
    const double door0 = z1, door1 = part[k + 1][0];  // the lintel over the door after part k
    m.AddRectangle({x0, lintel, door0}, {x0, h, door1}, 0, false, white);
    m.AddRectangle({x1, lintel, door0}, {x1, h, door1}, 0, true, white);
    m.AddRectangle({x0, lintel, door0}, {x1, lintel, door1}, 1, false, white);
  }
  for (double xc : {2.0, 6.2}) {
    m.AddRectangle({xc - 0.3, h - 0.01, 2.4}, {xc + 0.3, h - 0.01, 3.6}, 1, false, light);
    m.AddStandingBox({xc - 0.5, 0, 4.8}, {xc + 0.6, 0.75, 5.5}, white);  // a cabinet on the slab
  }
  testing::TempDir dir;
  scenegen::JobFileSettings job;
  job.eye = {1, 1.6, 1};
  job.target = {3, 1, 3};
  const Result<std::string> written = scenegen::WriteScene(m, dir.path(), "slab", job);
  ASSERT_TRUE(written.ok()) << written.error();
  ExpectNoEscapes(dir.File("slab.obj"), 0.25, 128);
}

}  // namespace
}  // namespace radfarm
