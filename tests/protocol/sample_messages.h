// One valid, non-trivial value of every message type (every field away from its default, so a
// field the codec forgets shows up), shared by the tests and the fuzz-corpus writer.
#pragma once

#include <vector>

#include "protocol/messages.h"

namespace radfarm::protocol::testing {

Bytes32 Pattern(uint8_t seed);          // 32 distinct bytes
std::vector<Message> SampleMessages();  // in variant order: one of each type
// Version 7's point messages of a direct-light start: a PointLease of patches, its PointResult
// with the punctual lights' share.
std::vector<Message> StartSamples();
// Version 8's of a refinement step's light scores: a PointLease of elements, its PointResult.
std::vector<Message> ScoreSamples();

// The sample of message type T.
template <typename T>
T SampleOf() {
  for (const Message& m : SampleMessages()) {
    if (const T* t = std::get_if<T>(&m)) return *t;
  }
  return T{};
}

}  // namespace radfarm::protocol::testing
