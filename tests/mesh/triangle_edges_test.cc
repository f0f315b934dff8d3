#include "mesh/triangle_edges.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

// Two triangles sharing the edge 1-2 (traversed both ways) and a third on 2-3 of the second: five
// edges, the shared ones listing both triangles in order.
TEST(TriangleEdgesTest, SharedEdgesListTheirTrianglesInOrder) {
  const std::vector<std::array<uint32_t, 3>> triangles{{0, 1, 2}, {2, 1, 3}, {3, 4, 2}};
  const TriangleEdges e = IndexEdges(triangles, 5);
  ASSERT_EQ(e.edge_of.size(), 9u);
  EXPECT_EQ(e.edges(), 7u);               // 0-1 1-2 2-0 1-3 3-2 3-4 4-2
  EXPECT_EQ(e.edge_of[1], e.edge_of[3]);  // 1-2 and 2-1
  EXPECT_EQ(e.edge_of[5], e.edge_of[8]);  // 3-2 and 2-3
  auto triangles_on = [&](uint32_t edge) {
    return std::vector<uint32_t>(e.sides.begin() + e.first[edge],
                                 e.sides.begin() + e.first[edge + 1]);
  };
  EXPECT_EQ(triangles_on(e.edge_of[1]), (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(triangles_on(e.edge_of[5]), (std::vector<uint32_t>{1, 2}));
  EXPECT_EQ(triangles_on(e.edge_of[0]), (std::vector<uint32_t>{0}));
  for (size_t i = 0; i < e.edge_of.size(); ++i) {
    for (size_t j = i + 1; j < e.edge_of.size(); ++j) {
      const bool same_pair = (i == 1 && j == 3) || (i == 5 && j == 8);
      EXPECT_EQ(e.edge_of[i] == e.edge_of[j], same_pair) << i << " " << j;
    }
  }
}

TEST(TriangleEdgesTest, NoTrianglesNoEdges) {
  const TriangleEdges e = IndexEdges({}, 0);
  EXPECT_EQ(e.edges(), 0u);
  EXPECT_TRUE(e.edge_of.empty());
}

}  // namespace
}  // namespace radfarm
