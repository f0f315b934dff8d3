#include "tests/protocol/session_test_helpers.h"

#include <gtest/gtest.h>

#include "protocol/frame_codec.h"

namespace radfarm::protocol::testing {

FarmSecret Secret(uint8_t fill) { return *FarmSecret::FromBytes(std::vector<uint8_t>(32, fill)); }

DecodedFrame Decode(const std::vector<uint8_t>& frame) {
  Result<DecodedFrame> decoded = DecodeFrame(frame);
  EXPECT_TRUE(decoded) << decoded.error();
  return decoded ? std::move(decoded).value() : DecodedFrame{};
}

}  // namespace radfarm::protocol::testing
