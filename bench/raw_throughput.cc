#include "bench/raw_throughput.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include "bench/stopwatch.h"
#include "core/batch_tracer.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "core/thread_pool.h"
#include "solve/local_solve.h"

namespace radfarm::bench {
namespace {

// Batches and their rays, in plan order; ray_begin[b] is batch b's first ray in the arrays.
struct RayWork {
  std::vector<Batch> batches;
  std::vector<size_t> ray_begin;
  std::vector<RTCRayHit> rays;
  std::vector<uint64_t> weights;
  std::vector<Vec3> directions;  // unrounded: Trace decides front or back with these
};

// Solves `rounds` rounds (the solver needs each round's results to plan the next) and keeps their
// batches.
std::vector<Batch> PlanRounds(uint32_t rounds, ThreadPool* pool,
                              std::vector<std::unique_ptr<BatchTracer>>* runners,
                              ProgressiveSolver* solver) {
  std::vector<Batch> batches;
  for (uint32_t r = 0; r < rounds; ++r) {
    const RoundPlan plan = solver->PlanRound(kLocalBatchRays);
    if (plan.batches.empty()) break;
    std::vector<BatchResult> results(plan.batches.size());
    pool->ParallelFor(plan.batches.size(), [&](unsigned worker, size_t b) {
      results[b] = (*runners)[worker]->Run(plan.batches[b]);
    });
    solver->ApplyRound(plan, results);
    batches.insert(batches.end(), plan.batches.begin(), plan.batches.end());
  }
  return batches;
}

// The rays as RayCaster::Trace builds them: origin moved into Embree's frame and lifted off the
// surface along the shooter's normal, then rounded to float.
void GenerateRays(const PatchScene& scene, const RayCaster& caster, const RaySampler& sampler,
                  RayWork* work) {
  size_t total = 0;
  for (const Batch& b : work->batches) {
    work->ray_begin.push_back(total);
    total += b.ray_count;
  }
  work->rays.resize(total);
  work->weights.resize(total);
  work->directions.resize(total);
  for (size_t bi = 0; bi < work->batches.size(); ++bi) {
    const Batch& b = work->batches[bi];
    const Patch& shooter = scene.patches[b.shooter];
    for (uint32_t k = 0; k < b.ray_count; ++k) {
      const RaySample s =
          sampler.Sample(shooter, b.shooter, b.round, caster.origin_offset(), b.first_ray + k);
      caster.PrepareRay(s.origin, s.direction, shooter.normal,
                        &work->rays[work->ray_begin[bi] + k]);
      work->weights[work->ray_begin[bi] + k] = s.weight;
      work->directions[work->ray_begin[bi] + k] = s.direction;
    }
  }
}

// Cuts the batches into `threads` contiguous groups of about equal ray counts; group t is batches
// [first[t], first[t + 1]).
std::vector<size_t> SplitBatches(const RayWork& work, unsigned threads) {
  const size_t total = work.rays.size();
  std::vector<size_t> first{0};
  for (unsigned t = 1; t < threads; ++t) {
    const size_t target = total * t / threads;
    size_t b = first.back();
    while (b < work.batches.size() && work.ray_begin[b] < target) ++b;
    first.push_back(b);
  }
  first.push_back(work.batches.size());
  return first;
}

size_t RayIndex(const RayWork& work, size_t batch) {
  return batch < work.batches.size() ? work.ray_begin[batch] : work.rays.size();
}

// The stored rays [begin, end) as packets of 16 in Embree's packet layout; `valid` per packet.
constexpr int kPacket = 16;
struct alignas(64) PacketMask {  // Embree reads the mask with aligned vector loads
  std::array<int, kPacket> lanes;
};
struct Packets {
  std::vector<RTCRayHit16> rays;
  std::vector<PacketMask> valid;
};

void FillPackets(const RayWork& work, size_t begin, size_t end, Packets* packets) {
  const size_t count = (end - begin + kPacket - 1) / kPacket;
  packets->rays.resize(count);
  packets->valid.resize(count);
  for (size_t p = 0; p < count; ++p) {
    RTCRayHit16& ph = packets->rays[p];
    for (int l = 0; l < kPacket; ++l) {
      const size_t i = begin + p * kPacket + l;
      packets->valid[p].lanes[l] = i < end ? -1 : 0;
      const RTCRayHit& rh = work.rays[i < end ? i : begin];
      ph.ray.org_x[l] = rh.ray.org_x;
      ph.ray.org_y[l] = rh.ray.org_y;
      ph.ray.org_z[l] = rh.ray.org_z;
      ph.ray.dir_x[l] = rh.ray.dir_x;
      ph.ray.dir_y[l] = rh.ray.dir_y;
      ph.ray.dir_z[l] = rh.ray.dir_z;
      ph.ray.tnear[l] = rh.ray.tnear;
      ph.ray.tfar[l] = rh.ray.tfar;
      ph.ray.time[l] = rh.ray.time;
      ph.ray.mask[l] = rh.ray.mask;
      ph.ray.id[l] = rh.ray.id;
      ph.ray.flags[l] = rh.ray.flags;
      ph.hit.geomID[l] = rh.hit.geomID;
      ph.hit.primID[l] = rh.hit.primID;
    }
  }
}

// The packets' hits back in single-ray layout (only what CountHits reads).
void UnpackHits(const Packets& packets, size_t begin, size_t end, std::vector<RTCRayHit>* traced) {
  for (size_t i = begin; i < end; ++i) {
    const RTCRayHit16& ph = packets.rays[(i - begin) / kPacket];
    const size_t l = (i - begin) % kPacket;
    (*traced)[i].hit.geomID = ph.hit.geomID[l];
    (*traced)[i].hit.primID = ph.hit.primID[l];
  }
}

// Runs body(t) on `threads` std::threads and returns the wall time from start to the last join.
template <typename Body>
double TimeThreads(unsigned threads, const Body& body) {
  const Stopwatch clock;
  if (threads == 1) {  // on the calling thread, as ThreadPool runs a pool of one
    body(0);
    return clock.Seconds();
  }
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back([&body, t] { body(t); });
  for (std::thread& th : pool) th.join();
  return clock.Seconds();
}

// Counts the traced rays' fates per batch the way BatchTracer does.
std::vector<BatchResult> CountHits(const PatchScene& scene, const RayCaster& caster,
                                   const RayWork& work, const std::vector<RTCRayHit>& traced) {
  std::vector<BatchResult> results(work.batches.size());
  std::vector<uint64_t> weight(scene.patches.size());
  for (size_t b = 0; b < work.batches.size(); ++b) {
    std::vector<uint32_t> touched;
    for (size_t i = work.ray_begin[b]; i < RayIndex(work, b + 1); ++i) {
      const RTCRayHit& rh = traced[i];
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        results[b].escaped_weight += work.weights[i];
        ++results[b].escaped_rays;
        continue;
      }
      const uint32_t patch = caster.PatchOfTriangle(rh.hit.primID);
      if (Dot(work.directions[i], scene.patches[patch].normal) >= 0) {
        results[b].back_weight += work.weights[i];
        ++results[b].back_rays;
        continue;
      }
      if (weight[patch] == 0) touched.push_back(patch);
      weight[patch] += work.weights[i];
    }
    std::sort(touched.begin(), touched.end());
    for (uint32_t p : touched) {
      results[b].hits.push_back({p, weight[p]});
      weight[p] = 0;
    }
  }
  return results;
}

}  // namespace

RawThroughput MeasureRawThroughput(const BenchScene& bench_scene, const SolverSettings& settings,
                                   uint32_t rounds, int repetitions, unsigned threads,
                                   uint64_t max_rays) {
  const PatchScene& scene = bench_scene.patches();
  const RayCaster caster(scene);
  ProgressiveSolver solver(scene, settings);
  ThreadPool pool(threads);
  std::vector<std::unique_ptr<BatchTracer>> runners;
  for (unsigned w = 0; w < pool.size(); ++w) {
    runners.push_back(std::make_unique<BatchTracer>(scene, caster, solver.sampler()));
  }
  RayWork work;
  work.batches = PlanRounds(rounds, &pool, &runners, &solver);
  const size_t planned_batches = work.batches.size();
  uint64_t planned_rays = 0;
  for (const Batch& b : work.batches) planned_rays += b.ray_count;
  if (max_rays > 0 && planned_rays > max_rays) {
    const uint64_t stride = (planned_rays + max_rays - 1) / max_rays;
    std::vector<Batch> kept;
    for (size_t b = 0; b < work.batches.size(); b += stride) kept.push_back(work.batches[b]);
    work.batches = std::move(kept);
  }
  GenerateRays(scene, caster, solver.sampler(), &work);
  const std::vector<size_t> group = SplitBatches(work, threads);

  RawThroughput out;
  out.scene = bench_scene.name;
  out.patch_size = bench_scene.patch_size;
  out.patches = scene.patches.size();
  out.rounds = solver.rounds_done();
  out.rays = work.rays.size();
  out.batches = work.batches.size();
  out.planned_rays = planned_rays;
  out.planned_batches = planned_batches;
  out.threads = threads;
  out.repetitions = repetitions;

  RTCScene embree = caster.embree_scene();
  std::vector<RTCRayHit> traced(work.rays.size());
  std::vector<BatchResult> results(work.batches.size());
  auto raw = [&] {
    std::copy(work.rays.begin(), work.rays.end(), traced.begin());  // untimed: reset tfar and hits
    return TimeThreads(threads, [&](unsigned t) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      const size_t end = RayIndex(work, group[t + 1]);
      for (size_t i = RayIndex(work, group[t]); i < end; ++i) {
        rtcIntersect1(embree, &context, &traced[i]);
      }
    });
  };
  std::vector<Packets> packets(threads);
  std::vector<Packets> packets_template(threads);
  for (unsigned t = 0; t < threads; ++t) {
    FillPackets(work, RayIndex(work, group[t]), RayIndex(work, group[t + 1]), &packets_template[t]);
  }
  auto packet = [&] {
    packets = packets_template;  // untimed: reset tfar and hits
    return TimeThreads(threads, [&](unsigned t) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      for (size_t p = 0; p < packets[t].rays.size(); ++p) {
        rtcIntersect16(packets[t].valid[p].lanes.data(), embree, &context, &packets[t].rays[p]);
      }
    });
  };
  auto runner = [&] {
    return TimeThreads(threads, [&](unsigned t) {
      runners[t]->RunMany(std::span(work.batches).subspan(group[t], group[t + 1] - group[t]),
                          results.data() + group[t]);
    });
  };
  std::vector<double> sink(threads);  // keeps the sampling loop from being optimised away
  auto sampling = [&] {
    return TimeThreads(threads, [&](unsigned t) {
      double sum = 0;
      RayBlock block;
      for (size_t b = group[t]; b < group[t + 1]; ++b) {
        const Batch& batch = work.batches[b];
        const ShotSampler shot = solver.sampler().Shot(scene.patches[batch.shooter], batch.shooter,
                                                       batch.round, caster.origin_offset());
        for (uint32_t done = 0; done < batch.ray_count; done += RayBlock::kSize) {
          const int count =
              static_cast<int>(std::min<uint32_t>(RayBlock::kSize, batch.ray_count - done));
          shot.SampleBlock(batch.first_ray + done, count, &block);
          sum += block.origin_x[0] + block.direction_x[count - 1];
        }
      }
      sink[t] = sum;
    });
  };
  const std::vector<size_t> starts = BatchTracer::GroupStarts(work.batches);
  auto pooled = [&] {
    const Stopwatch clock;
    // As LocalBatches hands them out: groups of short batches (BatchTracer::GroupStarts).
    pool.ParallelFor(starts.size() - 1, [&](unsigned worker, size_t g) {
      runners[worker]->RunMany(
          std::span(work.batches).subspan(starts[g], starts[g + 1] - starts[g]),
          results.data() + starts[g]);
    });
    return clock.Seconds();
  };

  // Warm-up (untimed): page in the arrays, and check that the raw loop finds the solver's hits.
  raw();
  runner();
  const bool same_as_single_rays = CountHits(scene, caster, work, traced) == results;
  packet();
  for (unsigned t = 0; t < threads; ++t) {
    UnpackHits(packets[t], RayIndex(work, group[t]), RayIndex(work, group[t + 1]), &traced);
  }
  const bool same_as_packets = CountHits(scene, caster, work, traced) == results;
  out.same_hits = same_as_single_rays && same_as_packets;
  std::printf(
      "%s (%zu patches) on %u threads: the tracer's hits %s the raw rtcIntersect1 loop's, %s "
      "the rtcIntersect16 loop's\n",
      out.scene.c_str(), out.patches, threads, same_as_single_rays ? "equal" : "DIFFER from",
      same_as_packets ? "equal" : "DIFFER from");
  for (const BatchResult& r : results) {
    out.escaped_rays += r.escaped_rays;
    out.back_rays += r.back_rays;
  }

  std::vector<double> packet_ratio, runner_ratio, pool_ratio;
  for (int rep = 0; rep < repetitions; ++rep) {
    out.raw_seconds.push_back(raw());
    out.packet_seconds.push_back(packet());
    out.runner_seconds.push_back(runner());
    out.pool_seconds.push_back(pooled());
    out.sample_seconds.push_back(sampling());
    packet_ratio.push_back(out.raw_seconds.back() / out.packet_seconds.back());
    runner_ratio.push_back(out.raw_seconds.back() / out.runner_seconds.back());
    pool_ratio.push_back(out.raw_seconds.back() / out.pool_seconds.back());
    std::printf(
        "%s (%zu patches) on %u threads, repetition %d: raw %.3f s, packets %.3f s, tracer %.3f s "
        "(%.1f %% of raw), pool %.3f s, sampling %.3f s\n",
        out.scene.c_str(), out.patches, threads, rep + 1, out.raw_seconds.back(),
        out.packet_seconds.back(), out.runner_seconds.back(), 100 * runner_ratio.back(),
        out.pool_seconds.back(), out.sample_seconds.back());
    std::fflush(stdout);
  }
  const double rays = double(out.rays);
  out.raw_rays_per_second = rays / Median(out.raw_seconds);
  out.packet_rays_per_second = rays / Median(out.packet_seconds);
  out.runner_rays_per_second = rays / Median(out.runner_seconds);
  out.pool_rays_per_second = rays / Median(out.pool_seconds);
  out.sample_rays_per_second = rays / Median(out.sample_seconds);
  out.packet_over_raw = Median(packet_ratio);
  out.runner_over_raw = Median(runner_ratio);
  out.pool_over_raw = Median(pool_ratio);
  return out;
}

}  // namespace radfarm::bench
