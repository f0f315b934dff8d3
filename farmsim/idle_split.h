// Where simulated agents' idle time went over a job (farm_bench's scaling table), from a
// SwarmReport: between the rounds and within them, and of the time within them, before each
// agent's first lease of a round (the round's start) and after its last result (its tail).
//
// A round's span runs from its first lease to its last result over all agents. The final
// gather's batches leased ahead of their round (round kGatherRound, daemon/jobs/gather_ahead.h)
// have no span: they run across the others, and an agent's time on them is busy time, within a
// round's span or between rounds, wherever it falls.
#pragma once

#include <cstddef>

#include "farmsim/agent_swarm.h"

namespace radfarm::sim {

// Fractions of agents x wall seconds.
struct IdleSplit {
  double between_rounds = 0;  // no round's span running, and not on the gather ahead
  double within_rounds = 0;   // in a round's span, computing nothing
  double round_starts = 0;    // of the span time: before the agent's first lease of the round
  double round_tails = 0;     // of the span time: after the agent's last result of the round
};

// All zero when `agents` or `wall_seconds` is zero.
IdleSplit SplitIdleTime(const SwarmReport& report, size_t agents, double wall_seconds);

}  // namespace radfarm::sim
