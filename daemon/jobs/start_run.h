// StartRun: one job's direct-light start under lease (job_start.cc): the request the compute
// thread handed over (start_handoff.h) and its patches cut into pieces leased to agents of
// protocol version 7 (display_pieces.h: a piece's items are patches here, not points).
#pragma once

#include <cstdint>

#include "daemon/jobs/display_pieces.h"
#include "daemon/jobs/start_handoff.h"

namespace radfarm::daemon {

// Steps of start runs carry this bit (DisplayPieces' step, in a lease id's high 32 bits), so a
// late result of a start is never taken for a piece of the display that follows, or of a later
// start of the same job (a refinement restart).
inline constexpr uint32_t kStartStepBit = 0x80000000u;

struct StartRun {
  uint64_t ticket = 0;
  StartRequest request;
  DisplayPieces pieces;
  double agent_seconds = 0;  // the accepted pieces' compute seconds, for the job's timeline
};

}  // namespace radfarm::daemon
