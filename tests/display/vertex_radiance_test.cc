// Vertex radiance: area-weighted averages within a surface, extrapolated at its border, sharp
// creases, and continuous shading across T-vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "display/display_stage.h"
#include "mesh/border_extrapolation.h"
#include "mesh/patch_mesh.h"
#include "tests/mesh/test_scenes.h"

namespace radfarm {
namespace {

using testing::SceneBuilder;

std::vector<Rgb> Uniform(const PatchMesh& mesh, Rgb value) {
  return std::vector<Rgb>(mesh.patch_scene().patches.size(), value);
}

DisplayMesh Averaged(const PatchMesh& mesh, const std::vector<Rgb>& radiosity) {
  return AveragedDisplay(mesh.display_topology(), mesh.patch_scene(), radiosity);
}

TEST(VertexRadianceTest, UniformRadianceStaysUniform) {
  Result<PatchMesh> mesh = PatchMesh::Build(testing::CornellBox(true), {40}, nullptr);
  ASSERT_TRUE(mesh.ok());
  const DisplayMesh d = Averaged(*mesh, Uniform(*mesh, {0.25, 0.5, 0.75}));
  ASSERT_FALSE(d.positions.empty());
  ASSERT_EQ(d.positions.size(), d.radiance.size());
  ASSERT_EQ(d.triangles.size(), d.triangle_patch.size());
  for (const Rgb& r : d.radiance) {
    EXPECT_NEAR(r.r, 0.25, 1e-14);
    EXPECT_NEAR(r.g, 0.5, 1e-14);
    EXPECT_NEAR(r.b, 0.75, 1e-14);
  }
}

TEST(VertexRadianceTest, CreaseKeepsTwoValues) {
  SceneBuilder s;
  s.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  s.AddFace({{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}});  // floor, up
  s.AddFace({{0, 0, 0}, {0, 2, 0}, {0, 2, 2}, {0, 0, 2}});  // wall at x = 0, facing +x
  Result<PatchMesh> mesh = PatchMesh::Build(s.scene(), {1}, nullptr);
  ASSERT_TRUE(mesh.ok());
  ASSERT_EQ(mesh->surface_count(), 2u);
  std::vector<Rgb> b;
  for (const Patch& p : mesh->patch_scene().patches)
    b.push_back(p.normal.y > 0.5 ? Rgb(1, 1, 1) : Rgb(3, 3, 3));
  const DisplayMesh d = Averaged(*mesh, b);
  EXPECT_EQ(d.positions.size(), 9u + 9u);  // each surface keeps its own corner vertices
  std::map<std::tuple<double, double, double>, std::vector<double>> at_position;
  for (size_t v = 0; v < d.positions.size(); ++v) {
    at_position[{d.positions[v].x, d.positions[v].y, d.positions[v].z}].push_back(d.radiance[v].r);
  }
  for (double z : {0.0, 1.0, 2.0}) {
    const std::vector<double>& values = at_position[{0.0, 0.0, z}];
    ASSERT_EQ(values.size(), 2u);
    EXPECT_EQ(std::min(values[0], values[1]), 1.0);
    EXPECT_EQ(std::max(values[0], values[1]), 3.0);
  }
}

Rgb Field(const Vec3& p) { return {1 + 2 * p.x + 3 * p.y, 2 - p.y, 5 + p.x}; }

// Builds the scene with patch size h.
std::unique_ptr<PatchMesh> MeshOf(const InputScene& scene, double h) {
  Result<PatchMesh> built = PatchMesh::Build(scene, {h}, nullptr);
  EXPECT_TRUE(built.ok());
  if (!built.ok()) return nullptr;
  return std::make_unique<PatchMesh>(std::move(built).value());
}

// The display of each patch given the field's value at its centre.
DisplayMesh LinearFieldDisplay(const PatchMesh& mesh) {
  std::vector<Rgb> b;
  for (const Patch& p : mesh.patch_scene().patches) b.push_back(Field(p.centre));
  return Averaged(mesh, b);
}

// Interpolated values along the segment x = 1, y in (0, y_max) (z = 0) agree from both sides.
void ExpectContinuousAtXEqualsOne(const PatchMesh& mesh, double y_max) {
  const DisplayMesh display = LinearFieldDisplay(mesh);
  for (int i = 1; i < 200; ++i) {
    const Vec3 p{1, y_max * i / 200.0, 0};
    std::vector<Rgb> left, right;
    for (size_t t = 0; t < display.triangles.size(); ++t) {
      if (!testing::Contains(display, t, p, 1e-12)) continue;
      const bool is_left = mesh.patch_scene().patches[display.triangle_patch[t]].centre.x < 1;
      (is_left ? left : right).push_back(testing::Interpolate(display, t, p));
    }
    ASSERT_FALSE(left.empty()) << p.y;
    ASSERT_FALSE(right.empty()) << p.y;
    for (const Rgb& r : right) {
      EXPECT_NEAR(r.r, left[0].r, 1e-12) << p.y;
      EXPECT_NEAR(r.g, left[0].g, 1e-12) << p.y;
      EXPECT_NEAR(r.b, left[0].b, 1e-12) << p.y;
    }
  }
}

// A linear field on one surface made of two input quads gridded differently: 2 cells along the
// shared edge on one side, 3 on the other (the trapezoid's far edge is longer).
class TVertexTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SceneBuilder s;
    s.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
    s.AddFace({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    s.AddFace({{1, 0, 0}, {2, -0.25, 0}, {2, 1.25, 0}, {1, 1, 0}});
    mesh_ = MeshOf(s.scene(), 0.5);
    ASSERT_NE(mesh_, nullptr);
    ASSERT_EQ(mesh_->surface_count(), 1u);
    ASSERT_EQ(mesh_->patch_scene().patches.size(), 4u + 9u);
    display_ = LinearFieldDisplay(*mesh_);
  }

  std::unique_ptr<PatchMesh> mesh_;
  DisplayMesh display_;
};

TEST_F(TVertexTest, ShadingIsContinuousAcrossTheSharedEdge) {
  ExpectContinuousAtXEqualsOne(*mesh_, 1);
}

// The same across an edge that is a T-junction in the input itself: one tall quad on the left,
// a square and a triangle on the right, each split its own way.
TEST(VertexRadianceTest, ShadingIsContinuousAcrossAnInputTJunction) {
  SceneBuilder s;
  s.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  s.AddFace({{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0}});
  s.AddFace({{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}});
  s.AddFace({{1, 1, 0}, {2, 1, 0}, {1, 2, 0}});
  const std::unique_ptr<PatchMesh> mesh = MeshOf(s.scene(), 0.3);
  ASSERT_NE(mesh, nullptr);
  ASSERT_EQ(mesh->surface_count(), 1u);
  ExpectContinuousAtXEqualsOne(*mesh, 2);
}

TEST_F(TVertexTest, LinearFieldIsReproducedClosely) {
  // Exact where a vertex is surrounded symmetrically (the centre of the left quad), close inside
  // the shared edge, where each side contributes patches of different shapes. (The outline is
  // extrapolated: BorderVerticesContinueALinearField.)
  for (size_t v = 0; v < display_.positions.size(); ++v) {
    const Vec3& p = display_.positions[v];
    const Rgb want = Field(p);
    if (Length(p - Vec3{0.5, 0.5, 0}) < 1e-12) {
      EXPECT_NEAR(display_.radiance[v].r, want.r, 1e-12);
    }
    if (std::fabs(p.x - 1) < 1e-12 && p.y > 1e-12 && p.y < 1 - 1e-12) {  // not the outline
      EXPECT_NEAR(display_.radiance[v].r, want.r, 0.6) << p.y;  // gradient 3.6, patch size 0.5
      EXPECT_NEAR(display_.radiance[v].g, want.g, 0.1) << p.y;
    }
  }
}

// On a grid, a border vertex's average is the field half a patch inside; extrapolated from its
// neighbour inside the surface it is the field at the border itself. Grid corners have no
// neighbour inside and keep the corner patch's value.
TEST(VertexRadianceTest, BorderVerticesContinueALinearField) {
  SceneBuilder s;
  s.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  s.AddFace({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}});
  const std::unique_ptr<PatchMesh> mesh = MeshOf(s.scene(), 0.5);
  ASSERT_NE(mesh, nullptr);
  ASSERT_EQ(mesh->patch_scene().patches.size(), 16u);
  const DisplayMesh display = LinearFieldDisplay(*mesh);
  int borders = 0, corners = 0;
  for (size_t v = 0; v < display.positions.size(); ++v) {
    const Vec3& p = display.positions[v];
    const bool on_x = p.x < 1e-12 || p.x > 2 - 1e-12, on_y = p.y < 1e-12 || p.y > 2 - 1e-12;
    SCOPED_TRACE(::testing::Message() << p.x << ", " << p.y);
    if (on_x && on_y) {
      ++corners;
      const Rgb patch = Field({p.x < 1 ? 0.25 : 1.75, p.y < 1 ? 0.25 : 1.75, 0});
      EXPECT_NEAR(display.radiance[v].r, patch.r, 1e-12);
      continue;
    }
    const Rgb want = Field(p);  // inside, and on the border by extrapolation
    borders += on_x || on_y;
    EXPECT_NEAR(display.radiance[v].r, want.r, 1e-12);
    EXPECT_NEAR(display.radiance[v].g, want.g, 1e-12);
    EXPECT_NEAR(display.radiance[v].b, want.b, 1e-12);
  }
  EXPECT_EQ(corners, 4);
  EXPECT_EQ(borders, 12);
}

// A 3 x 3 grid of faces (vertices 4 x 4, numbered row by row): a border vertex far darker than the
// inside would extrapolate below zero and is clamped; vertices inside are never changed.
TEST(VertexRadianceTest, ExtrapolationIsClampedAtZero) {
  std::vector<std::vector<uint32_t>> rings;
  for (uint32_t y = 0; y < 3; ++y) {
    for (uint32_t x = 0; x < 3; ++x) {
      const uint32_t v = 4 * y + x;
      rings.push_back({v, v + 1, v + 5, v + 4});
    }
  }
  std::vector<Rgb> values(16, Rgb(3, 3, 3));
  values[1] = {1, 2, 4};  // on the bottom border; its neighbour inside is vertex 5
  ExtrapolateBorders(rings, &values);
  EXPECT_EQ(values[1], Rgb(0, 1, 5));
  EXPECT_EQ(values[5], Rgb(3, 3, 3));
  EXPECT_EQ(values[0], Rgb(3, 3, 3));  // a corner: no neighbour inside
}

TEST_F(TVertexTest, PatchesWithTVerticesAreTriangulatedThroughThem) {
  // Left patches along x = 1 have a right-hand corner on their edge; right patches have the left
  // side's midpoint on theirs. Each such patch gets one more display triangle.
  size_t quads = 0;
  for (const Patch& p : mesh_->patch_scene().patches) quads += p.corner_count == 4;
  ASSERT_EQ(quads, 13u);
  // Left edge vertices: y = 1/3 and 2/3 lie on the two left patches' edges; y = 1/2 on the middle
  // right patch's edge.
  EXPECT_EQ(display_.triangles.size(), 2 * quads + 2 + 1);
}

// The topology the display reads: every patch's corners once, the three T-vertices on the shared
// edge, and each ring its patch's corners with the T-vertices on its edges.
TEST_F(TVertexTest, TheTopologyListsCornersAndTVertices) {
  const DisplayTopology topology = mesh_->display_topology();
  const std::vector<Patch>& patches = mesh_->patch_scene().patches;
  ASSERT_EQ(topology.patch_count(), patches.size());
  ASSERT_EQ(topology.corner_begin.size(), patches.size() + 1);
  EXPECT_EQ(topology.vertex_count(), display_.positions.size());
  ASSERT_EQ(topology.edge_vertices.size(), 3u);
  std::vector<size_t> on_edges(patches.size(), 0);
  for (const DisplayTopology::EdgeVertex& e : topology.edge_vertices) {
    EXPECT_NEAR(topology.positions[e.vertex].x, 1, 1e-12);
    ++on_edges[e.patch];
  }
  for (uint32_t f = 0; f < patches.size(); ++f) {
    const uint32_t corners = topology.corner_begin[f + 1] - topology.corner_begin[f];
    EXPECT_EQ(corners, uint32_t(patches[f].corner_count)) << f;
    EXPECT_EQ(topology.rings[f].size(), corners + on_edges[f]) << f;
    for (uint32_t c = topology.corner_begin[f]; c < topology.corner_begin[f + 1]; ++c) {
      EXPECT_LT(Length(topology.corner_position[c] - topology.positions[topology.corner_vertex[c]]),
                1e-9);
    }
  }
}

}  // namespace
}  // namespace radfarm
