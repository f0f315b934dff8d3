// The BatchResult a simulated agent returns: not physics, but a result the master's
// CheckBatchOutcome accepts for that batch (docs/PROTOCOL.md), so energy keeps flowing and the
// job runs its rounds as a real one would.
//
// For the unit-weight samplers (random, sobol) every ray is a front hit, spread as evenly as
// possible over up to `spread` distinct patches other than the shooter (the shooter itself only
// in a one-patch scene), chosen by a hash of (seed, round, shooter, first_ray): deterministic, so
// a re-issued batch gets the same answer, and spread over the whole scene, so the next round has
// many shooters, as after a real round. Nothing escapes and nothing hits a back face.
// The grid sampler's weights depend on the ray directions; it is not simulated.
#pragma once

#include <cstdint>

#include "base/result.h"
#include "protocol/messages.h"

namespace radfarm::sim {

Result<protocol::BatchOutcome> MakeSimulatedResult(const protocol::AssignedBatch& batch,
                                                   uint32_t spread, double compute_seconds);

}  // namespace radfarm::sim
