#include "store/blob_codec.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

namespace radfarm::store {
namespace {

TEST(BlobCodecTest, LittleEndianLayout) {
  std::vector<uint8_t> bytes = EncodeRgbs(std::vector<Rgb>{Rgb(1.0, 0.5, -2.0)});
  ASSERT_EQ(bytes.size(), 24u);
  // 1.0 is 0x3FF0000000000000: the most significant byte comes last.
  EXPECT_EQ(bytes[7], 0x3F);
  EXPECT_EQ(bytes[6], 0xF0);
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[15], 0x3F);  // 0.5 = 0x3FE0...
  EXPECT_EQ(bytes[14], 0xE0);
  EXPECT_EQ(bytes[23], 0xC0);  // -2.0 = 0xC000...
}

TEST(BlobCodecTest, RejectsTruncatedBlobs) {
  std::vector<uint8_t> bytes(25);
  Result<std::vector<Rgb>> decoded = DecodeRgbs(bytes);
  ASSERT_FALSE(decoded.ok());
  EXPECT_NE(decoded.error().find("25 bytes"), std::string::npos) << decoded.error();
  EXPECT_FALSE(DecodeEnergy(std::vector<uint8_t>(31)).ok());
}

TEST(BlobCodecTest, EdgeValuesRoundTripBitIdentically) {
  const double denormal = std::numeric_limits<double>::denorm_min();
  std::vector<Rgb> values = {
      Rgb(0.0, -0.0, denormal), Rgb(1e308, -1e308, 4.9e-320),
      Rgb(std::numeric_limits<double>::max(), std::numeric_limits<double>::min(), 0.1)};
  Result<std::vector<Rgb>> back = DecodeRgbs(EncodeRgbs(values));
  ASSERT_TRUE(back.ok()) << back.error();
  ASSERT_EQ(back->size(), values.size());
  EXPECT_EQ(std::memcmp(back->data(), values.data(), values.size() * sizeof(Rgb)), 0);
}

}  // namespace
}  // namespace radfarm::store
