#include "protocol/scene_packing.h"

#include <gtest/gtest.h>
#include <zstd.h>

#include <string>
#include <vector>

#include "protocol/scene_transfer.h"

namespace radfarm::protocol {
namespace {

std::vector<uint8_t> Text(size_t size) {
  std::vector<uint8_t> b(size);
  for (size_t i = 0; i < size; ++i) b[i] = static_cast<uint8_t>("radiosity "[i % 10]);
  return b;
}

void ExpectRefused(const Result<std::vector<uint8_t>>& unpacked, const std::string& why) {
  ASSERT_FALSE(unpacked);
  EXPECT_NE(unpacked.error().find(why), std::string::npos) << unpacked.error();
}

TEST(ScenePackingTest, PackingIsDeterministicAndRoundTrips) {
  const std::vector<uint8_t> blob = Text(100000);
  const PackedScene a = PackScene(blob), b = PackScene(blob);
  EXPECT_EQ(a.compressed, b.compressed);
  EXPECT_EQ(a.hash, HashScene(blob));
  EXPECT_EQ(a.size, blob.size());
  EXPECT_LT(a.compressed.size(), blob.size() / 10);
  Result<std::vector<uint8_t>> back = UnpackScene(a.compressed, a.size, a.size);
  ASSERT_TRUE(back) << back.error();
  EXPECT_EQ(*back, blob);
}

TEST(ScenePackingTest, DeclaredSizesOutsideTheLimitAreRefusedBeforeDecompressing) {
  const PackedScene packed = PackScene(Text(5000));
  ExpectRefused(UnpackScene(packed.compressed, 5000, 4999), "declared size 5000 not in 1..4999");
  ExpectRefused(UnpackScene(packed.compressed, 0, 5000), "declared size 0");
  ExpectRefused(UnpackScene(packed.compressed, 4000, 5000),
                "zstd frame holds 5000 bytes, the chunks declared 4000");
}

TEST(ScenePackingTest, BrokenFramesAreRefused) {
  const std::vector<uint8_t> blob = Text(5000);
  ExpectRefused(UnpackScene(blob, 5000, 5000), "not a zstd frame");
  // A frame that does not say how much it holds (as streamed frames may not): refused rather
  // than decompressed blind.
  std::vector<uint8_t> streamed(ZSTD_compressBound(blob.size()));
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, 0);
  ZSTD_outBuffer out{streamed.data(), streamed.size(), 0};
  ZSTD_inBuffer in{blob.data(), blob.size(), 0};
  ASSERT_EQ(ZSTD_compressStream2(cctx, &out, &in, ZSTD_e_end), 0u);
  ZSTD_freeCCtx(cctx);
  streamed.resize(out.pos);
  ExpectRefused(UnpackScene(streamed, 5000, 5000), "zstd frame without its content size");
  // A frame cut short. (A flipped byte inside may still decompress: the SHA-256 of the result,
  // checked by UnpackReceived, is what catches that.)
  const std::vector<uint8_t> packed = PackScene(blob).compressed;
  ExpectRefused(UnpackScene(std::span(packed).first(packed.size() - 3), 5000, 5000),
                "cannot decompress");
}

}  // namespace
}  // namespace radfarm::protocol
