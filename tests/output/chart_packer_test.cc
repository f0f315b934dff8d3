// PackInto and PackSmallest: rectangles inside the square, none overlapping, the square as small
// as the search allows and a multiple of 4.
#include "output/chart_packer.h"

#include <gtest/gtest.h>

#include <random>

namespace radfarm {
namespace {

void ExpectDisjointInside(const std::vector<PackSize>& sizes, const PackedSquare& packed) {
  ASSERT_EQ(packed.at.size(), sizes.size());
  std::vector<int> owner(size_t(packed.side) * packed.side, -1);
  for (size_t i = 0; i < sizes.size(); ++i) {
    ASSERT_LE(packed.at[i][0] + sizes[i].width, packed.side) << i;
    ASSERT_LE(packed.at[i][1] + sizes[i].height, packed.side) << i;
    for (uint32_t y = 0; y < sizes[i].height; ++y) {
      for (uint32_t x = 0; x < sizes[i].width; ++x) {
        int& o = owner[size_t(packed.at[i][1] + y) * packed.side + packed.at[i][0] + x];
        ASSERT_EQ(o, -1) << "rectangles " << o << " and " << i << " overlap";
        o = int(i);
      }
    }
  }
}

std::vector<PackSize> RandomSizes(uint32_t seed, size_t count) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<uint32_t> side(3, 60);
  std::vector<PackSize> out;
  for (size_t i = 0; i < count; ++i) out.push_back({side(random), side(random)});
  return out;
}

TEST(ChartPackerTest, PacksWithoutOverlapInsideTheSmallestSquare) {
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    const std::vector<PackSize> sizes = RandomSizes(seed, 200);
    const std::optional<PackedSquare> packed = PackSmallest(sizes, 4096);
    ASSERT_TRUE(packed.has_value()) << seed;
    EXPECT_EQ(packed->side % 4, 0u);
    ExpectDisjointInside(sizes, *packed);
    double area = 0;
    for (const PackSize& s : sizes) area += double(s.width) * s.height;
    // The skyline packer fills most of the square.
    EXPECT_GT(area / (double(packed->side) * packed->side), 0.7) << seed;
  }
}

TEST(ChartPackerTest, RefusesWhatDoesNotFit) {
  EXPECT_FALSE(PackInto({{9, 2}}, 8).has_value());
  EXPECT_FALSE(PackInto({{8, 8}, {1, 1}}, 8).has_value());
  EXPECT_TRUE(PackInto({{8, 8}}, 8).has_value());
  EXPECT_FALSE(PackSmallest(RandomSizes(7, 200), 64).has_value());
}

}  // namespace
}  // namespace radfarm
