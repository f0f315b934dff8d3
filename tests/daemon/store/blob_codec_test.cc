#include "daemon/store/blob_codec.h"

#include <gtest/gtest.h>

namespace radfarm::store {
namespace {
TEST(BlobCodecTest, Placeholder) { EXPECT_EQ(EncodeRgbs(std::vector<Rgb>(2)).size(), 48u); }
}  // namespace
}  // namespace radfarm::store
