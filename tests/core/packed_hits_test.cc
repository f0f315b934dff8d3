#include "core/packed_hits.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace radfarm {
namespace {

std::vector<uint8_t> Packed(const std::vector<PatchHits>& hits) {
  std::vector<uint8_t> bytes;
  AppendPackedHits(hits, &bytes);
  return bytes;
}

TEST(PackedHitsTest, HitsRoundTripAndTakeTwoBytesWhereIdsAreCloseAndRaysWeighOne) {
  const std::vector<PatchHits> hits = {
      {0, 1}, {3, 2}, {100, 1}, {227, 1}, {UINT32_MAX, UINT64_MAX}};
  const std::vector<uint8_t> bytes = Packed(hits);
  // 0:1, 3:1, 97:1, 127:1 are a byte each, weights 1-2 a byte; the last id's delta takes 5 bytes
  // and the largest weight 10.
  EXPECT_EQ(bytes.size(), 2u + 2u + 2u + 2u + 5u + 10u);
  EXPECT_EQ(PackedHitsBytes(hits), bytes.size());
  size_t at = 0;
  std::vector<PatchHits> read = {{7, 7}};  // replaced
  EXPECT_EQ(ReadPackedHits(bytes, &at, hits.size(), &read), "");
  EXPECT_EQ(read, hits);
  EXPECT_EQ(at, bytes.size());
}

TEST(PackedHitsTest, ReadsFromAnOffsetAndStopsAfterTheCount) {
  std::vector<uint8_t> bytes = {0xaa};
  AppendPackedHits(std::vector<PatchHits>{{5, 1}, {9, 3}}, &bytes);
  AppendPackedHits(std::vector<PatchHits>{{2, 1}}, &bytes);  // the next list starts again at 0
  size_t at = 1;
  std::vector<PatchHits> first, second;
  ASSERT_EQ(ReadPackedHits(bytes, &at, 2, &first), "");
  ASSERT_EQ(ReadPackedHits(bytes, &at, 1, &second), "");
  EXPECT_EQ(first, (std::vector<PatchHits>{{5, 1}, {9, 3}}));
  EXPECT_EQ(second, (std::vector<PatchHits>{{2, 1}}));
  EXPECT_EQ(at, bytes.size());
}

TEST(PackedHitsTest, WhatTheFoldWouldRefuseDoesNotRead) {
  std::vector<PatchHits> read;
  const auto error_of = [&](const std::vector<uint8_t>& bytes, uint64_t count) {
    size_t at = 0;
    return ReadPackedHits(bytes, &at, count, &read);
  };
  EXPECT_EQ(error_of({4, 1, 0, 1}, 2), "hit 1 is out of patch order or has no weight");  // repeat
  EXPECT_EQ(error_of({4, 0}, 1), "hit 0 is out of patch order or has no weight");        // weight 0
  // A delta that wraps past 2^32 back below the previous id.
  EXPECT_EQ(error_of({4, 1, 0xff, 0xff, 0xff, 0xff, 0x0f, 1}, 2),
            "hit 1 is out of patch order or has no weight");
  // A delta over 32 bits.
  EXPECT_EQ(error_of({0x80, 0x80, 0x80, 0x80, 0x10, 1}, 1),
            "hit 0 is out of patch order or has no weight");
  EXPECT_EQ(error_of({4, 0x81}, 1), "hit 0 ends inside a number");
  std::vector<uint8_t> overlong(10, 0xff);
  overlong.push_back(0x01);
  EXPECT_EQ(error_of(overlong, 1), "hit 0 ends inside a number");  // over 64 bits
  // A count the bytes cannot hold is refused before anything is allocated for it.
  EXPECT_EQ(error_of({1, 1}, uint64_t{1} << 60), "2 bytes cannot hold 1152921504606846976 hits");
  EXPECT_TRUE(read.empty());
}

TEST(PackedHitsTest, VarintsRoundTripAtTheirEdges) {
  for (uint64_t v : {uint64_t{0}, uint64_t{127}, uint64_t{128}, uint64_t{16383}, uint64_t{16384},
                     uint64_t{UINT32_MAX}, UINT64_MAX}) {
    std::vector<uint8_t> bytes;
    AppendVarint(v, &bytes);
    size_t at = 0;
    EXPECT_EQ(ReadVarint(bytes, &at), v);
    EXPECT_EQ(PackedHitsBytes(std::vector<PatchHits>{{0, v}}), 1 + bytes.size());
    EXPECT_EQ(at, bytes.size());
    for (size_t n = 0; n < bytes.size(); ++n) {
      size_t short_at = 0;
      EXPECT_FALSE(ReadVarint(std::span(bytes).first(n), &short_at).has_value()) << v << " " << n;
    }
  }
}

}  // namespace
}  // namespace radfarm
