// What the handshake tests share: a secret of one repeated byte, and a frame decoded or failed.
#pragma once

#include <cstdint>
#include <vector>

#include "protocol/farm_secret.h"
#include "protocol/messages.h"

namespace radfarm::protocol::testing {

FarmSecret Secret(uint8_t fill);  // 32 bytes of `fill`
// DecodeFrame, with a test failure (and an empty frame) if it does not decode.
DecodedFrame Decode(const std::vector<uint8_t>& frame);

}  // namespace radfarm::protocol::testing
