// ThroughputEstimate: an agent's smoothed rays per second, measured from the results it returns,
// and what follows from it: how many leases it may hold and when a lease of it is overdue.
//
// Each result contributes (rays, busy seconds), where busy seconds run from the later of the
// lease's issue time and the agent's previous result: while an agent is kept busy its results
// arrive one batch-time apart; after an idle gap only the time since the lease counts. Rays and
// seconds are smoothed separately and divided, so a burst of results finishing together (one per
// agent thread) does not blow the estimate up as averaging the ratios would.
#pragma once

#include <cstdint>
#include <optional>

#include "daemon/scheduler/scheduler_options.h"
#include "daemon/scheduler/scheduler_types.h"

namespace radfarm::scheduler {

class ThroughputEstimate {
 public:
  // A result of `rays` rays for a lease issued at `issued`, received at `now`. Once measured, a
  // result of fewer than `min_rays` rays only marks the time: its busy time is mostly the fixed
  // cost of a batch (the round trip, the 1 ms floor), so the shots of a round's last few rays
  // (one or two per shooter) would otherwise measure a fast agent at a few thousand rays/s and
  // shrink every later batch to the minimum. The first measurement needs `min_rays` too: results
  // below it add up until they reach it (a first lease of two 20-ray batches answered after a
  // 100 ms stall would read the agent at 400 rays/s, and leases sized from that stay under
  // `min_rays` and could never correct it).
  void AddResult(uint64_t rays, TimePoint issued, TimePoint now, double smoothing,
                 uint64_t min_rays = 0);

  bool measured() const { return rays_ > 0; }
  // Smoothed rays per second; 0 before the first result.
  double rays_per_second() const;
  // The speed the agent reports of itself (its heartbeats: what it measured on its recent
  // batches, of an earlier job or round). Until the first result is measured, it sizes the
  // agent's leases (LeaseCapacity, LeaseBatches) instead of options.initial_leases, so that an
  // agent the farm already knows gets a full lease at once rather than two batches and a round
  // trip. It never replaces a measurement, and the expected times and deadlines of an unmeasured
  // agent stay options.unmeasured_expected_seconds: its first lease may wait on a scene fetch.
  // Not finite or not positive: no report.
  void SetReportedSpeed(double rays_per_second);

  // Leases to hold so the held work takes about options.target_lease_seconds:
  // max(1, floor(rays/s * target / batch_rays)) + spare_leases, at most max_leases_per_agent;
  // options.initial_leases (capped) before the first result, or at least that many sized by the
  // reported speed (SetReportedSpeed).
  // Plus floor(that target count * spare_lease_fraction). Never fewer than MeasurableBatches.
  uint32_t LeaseCapacity(double batch_rays, const SchedulerOptions& options) const;
  // Batches for one lease frame: those that fill target_lease_seconds, max(1, floor(rays/s *
  // target / batch_rays)), at most max_leases_per_agent; options.initial_leases before the first
  // result (or at least that many sized by the reported speed). The agent's own speed: a fast agent
  // gets big leases whatever the slowest one does. Never fewer than MeasurableBatches.
  uint32_t LeaseBatches(double batch_rays, const SchedulerOptions& options) const;
  // Batches of `batch_rays` rays that make a result of at least options.min_batch_rays rays, one
  // that AddResult measures (at most max_leases_per_agent): however low the estimate, a full lease
  // can correct it.
  static uint32_t MeasurableBatches(double batch_rays, const SchedulerOptions& options);
  // Seconds the agent needs for `rays` at its measured speed; options.unmeasured_expected_seconds
  // for any work before the first result.
  double ExpectedSeconds(uint64_t rays, const SchedulerOptions& options) const;

  // When a lease issued at `now` is overdue, given the rays the agent then holds (this lease
  // included): now + max(floor, multiple * held_rays / rays_per_second).
  TimePoint Deadline(uint64_t held_rays, TimePoint now, const SchedulerOptions& options) const;

 private:
  double rays_ = 0;     // smoothed rays per result
  double seconds_ = 0;  // smoothed busy seconds per result
  // Before the first measurement: the results so far, under min_rays together.
  double pending_rays_ = 0;
  double pending_seconds_ = 0;
  std::optional<TimePoint> last_result_;
  double reported_rays_per_second_ = 0;
  // The speed leases are sized by: the measured one, else the reported one (0: neither).
  double SizingSpeed() const;
  // options.initial_leases, at least MeasurableBatches, within [1, max_leases_per_agent].
  static uint32_t InitialLeases(double batch_rays, const SchedulerOptions& options);
  // floor(SizingSpeed() * target_lease_seconds / batch_rays); nullopt without a speed.
  std::optional<double> FilledBatches(double batch_rays, const SchedulerOptions& options) const;
  // `leases` at least MeasurableBatches (and, unmeasured, the initial leases), within the cap.
  uint32_t SizedLeases(double leases, double batch_rays, const SchedulerOptions& options) const;
};

}  // namespace radfarm::scheduler
