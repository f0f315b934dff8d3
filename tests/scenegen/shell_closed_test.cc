// The generated shell (walls, floors, ceilings, door openings) is closed: along every edge of every
// face, other faces' edges run the other way and cover it exactly once, T-junctions included (a
// door's sill meets the room's floor along part of its edge).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "scenegen/building.h"

namespace radfarm::scenegen {
namespace {

struct Edge {
  Vec3 a, b;
};

std::vector<Edge> ShellEdges(const SceneModel& model) {
  std::vector<Edge> edges;
  for (const ModelFace& f : model.faces()) {
    if (model.materials()[f.material].emission != Vec3{}) continue;  // panels are sheets
    for (size_t i = 0; i < f.vertices.size(); ++i) {
      edges.push_back({model.vertices()[f.vertices[i]],
                       model.vertices()[f.vertices[(i + 1) % f.vertices.size()]]});
    }
  }
  return edges;
}

double DistanceToLine(const Vec3& p, const Vec3& a, const Vec3& unit) {
  const Vec3 d = p - a;
  return Length(d - unit * Dot(d, unit));
}

// Length of [0, length] covered by the reversed edges on e's line, counting overlaps twice.
double CoveredLength(const Edge& e, const std::vector<Edge>& edges, double* union_length) {
  const double length = Length(e.b - e.a);
  const Vec3 unit = (e.b - e.a) / length;
  std::vector<std::pair<double, double>> spans;
  for (const Edge& g : edges) {
    if (DistanceToLine(g.a, e.a, unit) > 1e-9 || DistanceToLine(g.b, e.a, unit) > 1e-9) continue;
    if (Dot(g.b - g.a, unit) >= 0) continue;
    const double s0 = std::max(0.0, Dot(g.b - e.a, unit));
    const double s1 = std::min(length, Dot(g.a - e.a, unit));
    if (s1 > s0) spans.emplace_back(s0, s1);
  }
  std::sort(spans.begin(), spans.end());
  double sum = 0, covered = 0, reach = 0;
  for (const auto& [s0, s1] : spans) {
    sum += s1 - s0;
    covered += std::max(0.0, s1 - std::max(s0, reach));
    reach = std::max(reach, s1);
  }
  *union_length = covered;
  return sum;
}

void ExpectClosed(const BuildingParams& p) {
  Result<SceneModel> model = GenerateBuilding(p, /*with_furniture=*/false);
  ASSERT_TRUE(model.ok()) << model.error();
  const std::vector<Edge> edges = ShellEdges(*model);
  ASSERT_GT(edges.size(), 0u);
  int open = 0;
  for (const Edge& e : edges) {
    double covered = 0;
    const double sum = CoveredLength(e, edges, &covered);
    const double length = Length(e.b - e.a);
    if (std::fabs(covered - length) > 1e-9 || std::fabs(sum - length) > 1e-9) {
      if (++open <= 5) {
        ADD_FAILURE() << "edge (" << e.a.x << " " << e.a.y << " " << e.a.z << ") -> (" << e.b.x
                      << " " << e.b.y << " " << e.b.z << ") of length " << length << ": covered "
                      << covered << " (" << sum << " counting overlaps)";
      }
    }
  }
  EXPECT_EQ(open, 0);
}

TEST(ShellClosed, OneRoom) { ExpectClosed({.floors = 1, .rooms_x = 1, .rooms_z = 1}); }

TEST(ShellClosed, RoomsWithDoorsOnTwoStoreys) {
  ExpectClosed({.floors = 2, .rooms_x = 3, .rooms_z = 2, .seed = 5});
}

TEST(ShellClosed, OddRoomSizesAndWindows) {
  ExpectClosed({.floors = 1,
                .rooms_x = 2,
                .rooms_z = 3,
                .room_width = 3.3,
                .room_depth = 5.7,
                .room_height = 2.7,
                .seed = 11,
                .windows = true});
}

// The check itself finds an open edge: a shell without one room's ceiling is not closed.
TEST(ShellClosed, CheckFindsAMissingFace) {
  Result<SceneModel> model = GenerateBuilding({.floors = 1, .rooms_x = 1, .rooms_z = 1}, false);
  ASSERT_TRUE(model.ok());
  SceneModel holed;
  for (const ModelMaterial& m : model->materials()) holed.AddMaterial(m);
  for (const ModelFace& f : model->faces()) {
    if (model->materials()[f.material].name == "ceiling") continue;
    std::vector<Vec3> corners;
    for (uint32_t v : f.vertices) corners.push_back(model->vertices()[v]);
    holed.AddFace(corners, f.material);
  }
  const std::vector<Edge> edges = ShellEdges(holed);
  int open = 0;
  for (const Edge& e : edges) {
    double covered = 0;
    CoveredLength(e, edges, &covered);
    open += std::fabs(covered - Length(e.b - e.a)) > 1e-9;
  }
  EXPECT_EQ(open, 4);  // the four walls' top edges
}

}  // namespace
}  // namespace radfarm::scenegen
