// Punctual lights (core/punctual_light.h) on the wire (schema/punctual_light.fbs), for the job
// bundle and the scene blob alike.
#pragma once

#include <flatbuffers/flatbuffers.h>

#include <string_view>
#include <vector>

#include "base/result.h"
#include "core/punctual_light.h"
#include "punctual_light_generated.h"

namespace radfarm::codec {

// The lights as a vector to store in a table; 0 (the field left out) when there are none.
flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<wire::WireLight>>> EncodeLights(
    flatbuffers::FlatBufferBuilder& fbb, const std::vector<PunctualLight>& lights);

// The lights of a verified buffer (null: none), each checked (PunctualLightProblem); errors name
// the blob `kind` and the light.
Result<std::vector<PunctualLight>> DecodeLights(
    const flatbuffers::Vector<flatbuffers::Offset<wire::WireLight>>* lights, std::string_view kind);

}  // namespace radfarm::codec
