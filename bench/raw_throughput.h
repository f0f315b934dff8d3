// Section 2 of the report: how close the solver's ray loop comes to Embree's own closest-hit speed.
// The rays of the first rounds of a solve are generated once, stored as RTCRayHit exactly as
// RayCaster would hand them to Embree, and then traced on the same threads:
//   raw:    a bare rtcIntersect1 loop over the stored rays, one contiguous chunk per thread (the
//           yardstick: the solver's loop should come close to it);
//   packet: the same stored rays as packets of 16 consecutive rays (rtcIntersect16, converted to
//           Embree's packet layout untimed): what Embree's packet query alone gives on these rays;
//   runner: BatchTracer::RunMany over the same batches, the same chunks per thread (ray
//           generation, tracing and hit counting: the solver's whole per-ray work);
//   pool:   the same batches through ThreadPool::ParallelFor, in groups of short batches as
//           Solve() schedules them (BatchTracer::GroupStarts);
// and, to show where the difference goes, the sampling alone (ShotSampler::SampleBlock, as
// BatchTracer calls it, no tracing) over the same batches and chunks.
#pragma once

#include <cstdint>
#include <vector>

#include "bench/bench_scene.h"
#include "core/solver_settings.h"

namespace radfarm::bench {

struct RawThroughput {
  std::string scene;
  double patch_size = 0;
  size_t patches = 0;
  uint32_t rounds = 0;
  uint64_t rays = 0;
  size_t batches = 0;
  // The rounds' rays and batches before a cap kept every k-th batch (equal to rays and batches
  // when nothing was dropped).
  uint64_t planned_rays = 0;
  size_t planned_batches = 0;
  unsigned threads = 0;
  int repetitions = 0;
  // One per repetition.
  std::vector<double> raw_seconds, packet_seconds, runner_seconds, pool_seconds, sample_seconds;
  double raw_rays_per_second = 0;  // medians
  double packet_rays_per_second = 0;
  double runner_rays_per_second = 0;
  double pool_rays_per_second = 0;
  double sample_rays_per_second = 0;
  // Medians of the per-repetition ratios (each repetition times all three back to back, so the
  // ratio sees the same machine load).
  double packet_over_raw = 0;
  double runner_over_raw = 0;
  double pool_over_raw = 0;
  // The raw loops' hits, counted per batch as BatchTracer counts them, equal the solver's results.
  bool same_hits = false;
  uint64_t escaped_rays = 0;
  uint64_t back_rays = 0;
};

// Plans and solves `rounds` rounds of `settings` on the scene (untimed) to obtain their batches,
// then times the loops `repetitions` times each on `threads` threads. With max_rays > 0 and more
// rays planned, only every k-th batch is traced (k keeping about max_rays): the
// batches' sizes and shooters stay those of the whole rounds, and the stored rays fit in memory
// (a default solve's first rounds at 10^6 patches hold several hundred million rays).
RawThroughput MeasureRawThroughput(const BenchScene& scene, const SolverSettings& settings,
                                   uint32_t rounds, int repetitions, unsigned threads,
                                   uint64_t max_rays = 0);

}  // namespace radfarm::bench
