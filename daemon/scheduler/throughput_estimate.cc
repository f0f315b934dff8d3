#include "daemon/scheduler/throughput_estimate.h"

#include <algorithm>
#include <cmath>

namespace radfarm::scheduler {
namespace {

// Results on the same fake-clock tick, or a clock of coarse resolution, still take some time.
constexpr double kMinBusySeconds = 1e-3;

}  // namespace

void ThroughputEstimate::AddResult(uint64_t rays, TimePoint issued, TimePoint now, double smoothing,
                                   uint64_t min_rays) {
  const TimePoint start = last_result_ ? std::max(issued, *last_result_) : issued;
  const double seconds =
      std::max(kMinBusySeconds, std::chrono::duration<double>(now - start).count());
  if (!measured()) {
    pending_rays_ += double(rays);
    pending_seconds_ += seconds;
    if (pending_rays_ >= double(min_rays) && pending_rays_ > 0) {
      rays_ = pending_rays_;
      seconds_ = pending_seconds_;
    }
  } else if (rays >= min_rays) {
    rays_ += smoothing * (double(rays) - rays_);
    seconds_ += smoothing * (seconds - seconds_);
  }
  // A result too small to count still ends the agent's busy time so far.
  last_result_ = std::max(now, last_result_.value_or(now));
}

double ThroughputEstimate::rays_per_second() const { return measured() ? rays_ / seconds_ : 0; }

void ThroughputEstimate::SetReportedSpeed(double rays_per_second) {
  reported_rays_per_second_ =
      std::isfinite(rays_per_second) && rays_per_second > 0 ? rays_per_second : 0;
}

double ThroughputEstimate::SizingSpeed() const {
  return measured() ? rays_per_second() : reported_rays_per_second_;
}

uint32_t ThroughputEstimate::InitialLeases(double batch_rays, const SchedulerOptions& options) {
  const uint32_t cap = std::max<uint32_t>(1, options.max_leases_per_agent);
  return std::clamp<uint32_t>(
      std::max(options.initial_leases, MeasurableBatches(batch_rays, options)), 1, cap);
}

std::optional<double> ThroughputEstimate::FilledBatches(double batch_rays,
                                                        const SchedulerOptions& options) const {
  if (SizingSpeed() <= 0) return std::nullopt;
  return std::floor(SizingSpeed() * options.target_lease_seconds / std::max(1.0, batch_rays));
}

uint32_t ThroughputEstimate::SizedLeases(double leases, double batch_rays,
                                         const SchedulerOptions& options) const {
  leases = std::max(leases, double(MeasurableBatches(batch_rays, options)));
  // A reported speed only adds to the initial leases; a measured one decides alone.
  if (!measured()) leases = std::max(leases, double(InitialLeases(batch_rays, options)));
  return static_cast<uint32_t>(
      std::clamp(leases, 1.0, double(std::max<uint32_t>(1, options.max_leases_per_agent))));
}

uint32_t ThroughputEstimate::LeaseCapacity(double batch_rays,
                                           const SchedulerOptions& options) const {
  const std::optional<double> filled = FilledBatches(batch_rays, options);
  if (!filled) return InitialLeases(batch_rays, options);
  const double fill = std::max(1.0, *filled);
  const double spare =
      double(options.spare_leases) + std::floor(fill * std::max(0.0, options.spare_lease_fraction));
  return SizedLeases(fill + spare, batch_rays, options);
}

uint32_t ThroughputEstimate::LeaseBatches(double batch_rays,
                                          const SchedulerOptions& options) const {
  const std::optional<double> filled = FilledBatches(batch_rays, options);
  if (!filled) return InitialLeases(batch_rays, options);
  return SizedLeases(*filled, batch_rays, options);
}

uint32_t ThroughputEstimate::MeasurableBatches(double batch_rays, const SchedulerOptions& options) {
  const uint32_t cap = std::max<uint32_t>(1, options.max_leases_per_agent);
  const double batches = std::ceil(double(options.min_batch_rays) / std::max(1.0, batch_rays));
  return static_cast<uint32_t>(std::clamp(batches, 1.0, double(cap)));
}

double ThroughputEstimate::ExpectedSeconds(uint64_t rays, const SchedulerOptions& options) const {
  if (rays == 0) return 0;
  return measured() ? double(rays) / rays_per_second() : options.unmeasured_expected_seconds;
}

TimePoint ThroughputEstimate::Deadline(uint64_t held_rays, TimePoint now,
                                       const SchedulerOptions& options) const {
  const double expected =
      measured() ? double(held_rays) / rays_per_second() : options.unmeasured_expected_seconds;
  const auto scaled = std::chrono::duration_cast<Duration>(
      std::chrono::duration<double>(options.deadline_multiple * expected));
  return now + std::max(options.deadline_floor, scaled);
}

}  // namespace radfarm::scheduler
