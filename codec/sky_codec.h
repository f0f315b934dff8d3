// The sky (core/sky.h) on the wire (schema/sky.fbs), for the job bundle and the scene blob alike.
#pragma once

#include <flatbuffers/flatbuffers.h>

#include <string_view>

#include "base/result.h"
#include "core/sky.h"
#include "sky_generated.h"

namespace radfarm::codec {

// The sky as a table to store; 0 (the field left out) for no sky (SkyKind::kNone).
flatbuffers::Offset<wire::WireSky> EncodeSky(flatbuffers::FlatBufferBuilder& fbb, const Sky& sky);

// The sky of a verified buffer (null: none), checked (SkyProblem, and no kNone on the wire);
// errors name the blob `kind`.
Result<Sky> DecodeSky(const wire::WireSky* sky, std::string_view kind);

}  // namespace radfarm::codec
