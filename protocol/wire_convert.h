// Internal: between the C++ messages (messages.h) and the FlatBuffers tables generated from
// schema/*.fbs. Only protocol/*.cc include this, so users of the library never see FlatBuffers.
#pragma once

#include <cstdint>

#include "base/result.h"
#include "frame_generated.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

// Adds `message` to `fbb` as a union value written in protocol `version` (a LeaseResult's hits are
// packed from kPackedHitsVersion on); `type` receives its union tag.
flatbuffers::Offset<void> BuildPayload(flatbuffers::FlatBufferBuilder& fbb, const Message& message,
                                       uint16_t version, wire::Payload* type);

// Reads the payload of a frame that passed the FlatBuffers verifier. Rejects unknown payload
// types, missing fields, unknown enum values and misaligned struct vectors; value ranges are
// CheckMessage's job. The frame's own version says how a LeaseResult holds its hits.
Result<Message> ReadPayload(const wire::Frame& frame);

}  // namespace radfarm::protocol
