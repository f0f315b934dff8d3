// Context-free checks of a message's values: lengths, ranges, enum values, finite numbers, sorted
// hits. The frame decoder runs them on every incoming frame, ProtocolSession::Encode on every
// outgoing one. Checks that need context (the scene's patch count, the batch's ray count) are in
// batch_validation.h.
#pragma once

#include "base/result.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

// OK, or an error naming the message and the field ("LeaseAssignment batch 0: shooter 9 >=
// patch_count 4").
Status CheckMessage(const Message& message);

// The context-free rules of one batch's result (an entry of a LeaseResult): hits in strictly
// increasing patch order with no zero weight, compute_seconds finite and >= 0.
Status CheckOutcomeValues(const BatchOutcome& result);

// The agent name rule: 1..kMaxAgentNameBytes of [A-Za-z0-9._:@-] (it goes into logs).
bool IsValidAgentName(std::string_view name);

}  // namespace radfarm::protocol
