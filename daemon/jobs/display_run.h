// DisplayRun: one finished job's display on its way (job_display.cc): its draft, the step's pieces
// leased to agents (display_pieces.h), and the frames between the two: a piece as a PointLease,
// a PointResult checked against the piece it answers.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "base/cpu_clock.h"
#include "base/result.h"
#include "core/job_timeline.h"
#include "daemon/jobs/display_draft.h"
#include "daemon/jobs/display_pieces.h"
#include "display/point_work.h"
#include "protocol/messages.h"
#include "store/job_store.h"

namespace radfarm::daemon {

struct SolveShown {
  uint32_t round = 0;
  uint64_t rays = 0;
};

struct DisplayRun {
  uint64_t serial = 0;  // tells this run's callbacks from an earlier run's of the same job
  std::string reason;   // why the rounds ended, for the job's `done` event
  uint32_t round = 0;   // of the checkpoint whose solution it shows
  // The finished solve's round and rays as its runner showed them last: a status read from the
  // store before the rounds ended would otherwise show fewer while the display is drawn.
  SolveShown solve;
  std::shared_ptr<DisplayDraft> draft;  // null until planned
  // The step leased to agents; empty while the draft is on the compute thread.
  std::optional<DisplayPieces> pieces;
  uint32_t leased_steps = 0, local_steps = 0;
  // For its ETA: the rays forecast before it (RoundDriver::display_rays_forecast), those its
  // applied steps cast, and when it started.
  uint64_t forecast_rays = 0;
  uint64_t rays_done = 0;
  uint64_t started_ms = 0;
  // The job's timeline (core/job_timeline.h): the rounds', then the agents' display pieces as
  // they come, and the master's wall and CPU seconds over the whole display at its end (the
  // whole process's, as for the rounds).
  JobTimeline timeline;
  LapClock clock;
};

// The seconds `run` has left at `now_ms`: its forecast rays still to cast at the pace of those
// cast so far; nullopt before a step is applied or once the forecast is spent (the last steps'
// size is unknown until the light is seen).
std::optional<double> DisplaySecondsLeft(const DisplayRun& run, uint64_t now_ms);

// Work of fewer items (a display step's points, a start's patches) is traced here: its leases
// would cost more round trips than rays.
inline constexpr size_t kLocalPiecesWork = 64;
// How long an agent has for a piece before an idle agent may take it as well: several times what
// an office desktop spends on the largest piece.
inline constexpr std::chrono::milliseconds kPieceLeaseTime{60000};

// Points a lease carries: about a quarter of an agent's share of the step, so that a step ends
// with the agents finishing close together, within [kMinLeasePoints, protocol::kMaxLeasePoints].
inline constexpr size_t kMinLeasePoints = 256;
size_t PiecePoints(size_t points, size_t agents);

// Piece `lease` of `work` (points, or a start's patches) as the frame that leases it.
protocol::PointLeaseMsg MakePointLease(store::JobId job, const PieceLease& lease,
                                       const PointWork& work, const protocol::SceneHash& context,
                                       uint32_t lease_ms);

// The values of `result`, which answers points [begin, end) of `work`: one value per point in
// each list the work asked for and none in the others. Errors name the list.
Result<PointValues> ValuesOfResult(const protocol::PointResultMsg& result, const PointWork& work,
                                   size_t begin, size_t end);

}  // namespace radfarm::daemon
