// The block paths of the ray loop (ScrambledSobol4::Points, ShotSampler::SampleBlock,
// RayCaster::TraceBlock) against the one-ray paths they replace in BatchTracer: a fast path must
// give the same bits, or the golden renders and the farm's determinism would move.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <map>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/batch_tracer.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"
#include "core/sobol.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(RayBlockTest, SobolPointsMatchPointIncludingTheWrapAt2To32) {
  const ScrambledSobol4 sobol(77);
  for (uint32_t first : {0u, 1u, 63u, 1000u, (1u << 20) - 5, 0xffffffffu - 40}) {
    double u[4][RayBlock::kSize];
    double* const out[4] = {u[0], u[1], u[2], u[3]};
    sobol.Points(first, RayBlock::kSize, out);
    for (int i = 0; i < RayBlock::kSize; ++i) {
      const auto expected = sobol.Point(first + static_cast<uint32_t>(i));
      for (int d = 0; d < 4; ++d) {
        ASSERT_TRUE(SameBits(u[d][i], expected[d]))
            << "first " << first << " i " << i << " d " << d;
      }
    }
  }
}

// The sampler's own cos and sin (no C library call, so every CPU rounds them alike) against
// std::cos and std::sin, across the quadrant boundaries.
TEST(RayBlockTest, CosineDirectionsFollowTheExactAngle) {
  const Vec3 t{1, 0, 0}, b{0, 1, 0}, n{0, 0, 1};
  for (double v : {0.0, 1e-9, 0.1, 0.25 - 1e-12, 0.25, 0.3, 0.5, 0.6, 0.75, 0.9, 1 - 0x1.0p-32}) {
    for (double u : {0.0, 0.3, 0.99}) {
      const Vec3 d = SampleCosineDirection(t, b, n, u, v);
      const double phi = 2 * M_PI * v, r = std::sqrt(u);
      EXPECT_NEAR(d.x, r * std::cos(phi), 1e-9) << "v " << v;
      EXPECT_NEAR(d.y, r * std::sin(phi), 1e-9) << "v " << v;
      EXPECT_NEAR(Length(d), 1.0, 1e-9) << "v " << v;
    }
  }
}

// A box of quads and triangles (a disc) far from the origin, so the caster's centring matters.
// The first disc patch's normal is tilted 0.2 rad off its plane: TraceBlock takes a hit's side
// from Embree's triangle normal only where that cannot disagree with the patch's normal, and must
// match Trace there too.
PatchScene MixedScene() {
  const Vec3 offset{1e4, -3e3, 2e3};
  PatchScene scene = testing::MakeClosedBox(offset, offset + Vec3{3, 2, 2.5}, 4, {});
  const size_t first_disc_patch = scene.patches.size();
  testing::AddDisc(offset + Vec3{1.5, 1, 1}, Normalize(Vec3{0.3, -0.2, 1}), 0.6, 7, {}, &scene);
  Vec3& tilted = scene.patches[first_disc_patch].normal;
  Vec3 t, b;
  OrthonormalBasis(tilted, &t, &b);
  tilted = Normalize(tilted + t * std::tan(0.2));
  return scene;
}

TEST(RayBlockTest, SampleBlockAndTraceBlockMatchSampleAndTrace) {
  // Some patches two-sided: TraceBlock's packets (16 rays) and its last rays one by one must both
  // go through the front-only filter as Trace does.
  PatchScene scene = MixedScene();
  for (size_t i = 1; i < scene.patches.size(); i += 5) scene.patches[i].two_sided = true;
  const RayCaster caster(scene);
  for (SamplerKind kind : {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 11, 4.0);
    for (uint32_t id = 0; id < scene.patches.size(); id += 3) {
      const Patch& patch = scene.patches[id];
      const ShotSampler shot = sampler.Shot(patch, id, 2, caster.origin_offset());
      RayBlock block;
      RayHit hits[RayBlock::kSize];
      // The grid's shot has a fixed size: its rays past the end do not exist (their rows would
      // be read out of bounds).
      const uint64_t late = kind == SamplerKind::kGrid
                                ? sampler.FixedRaysPerShot() - RayBlock::kSize
                                : uint64_t{3000};
      ASSERT_GT(late, 37u);
      for (uint64_t first : {uint64_t{0}, uint64_t{37}, late}) {
        for (int count : {1, 16, 17, 47, RayBlock::kSize}) {
          shot.SampleBlock(first, count, &block);
          caster.TraceBlock(block, patch.normal, hits);
          ASSERT_EQ(block.count, count);
          for (int i = 0; i < count; ++i) {
            const RaySample ray = shot.Sample(first + i);
            ASSERT_TRUE(SameBits(block.origin_x[i], ray.origin.x) &&
                        SameBits(block.origin_y[i], ray.origin.y) &&
                        SameBits(block.origin_z[i], ray.origin.z) &&
                        SameBits(block.direction_x[i], ray.direction.x) &&
                        SameBits(block.direction_y[i], ray.direction.y) &&
                        SameBits(block.direction_z[i], ray.direction.z))
                << SamplerName(kind) << " patch " << id << " ray " << first + i;
            ASSERT_EQ(block.weight[i], ray.weight);
            const RayHit hit = caster.Trace(ray.origin, ray.direction, patch.normal);
            ASSERT_EQ(hits[i].patch, hit.patch) << SamplerName(kind) << " ray " << first + i;
            ASSERT_EQ(hits[i].front, hit.front) << SamplerName(kind) << " ray " << first + i;
          }
        }
      }
    }
  }
}

// What an agent keeps of a scene, the patches' shapes and sides (agent/prepared_scene.h), must
// trace every batch exactly as the whole scene does, two-sided patches included.
TEST(RayBlockTest, BatchesFromTheShapesMatchBatchesFromTheScene) {
  PatchScene scene = MixedScene();
  for (size_t i = 0; i < scene.patches.size(); i += 4) scene.patches[i].two_sided = true;
  std::vector<PatchShape> shapes(scene.patches.begin(), scene.patches.end());
  std::vector<uint8_t> two_sided;
  for (const Patch& p : scene.patches) two_sided.push_back(p.two_sided ? 1 : 0);
  const RayCaster whole(scene), from_shapes(shapes, two_sided);
  ASSERT_EQ(whole.origin_offset(), from_shapes.origin_offset());
  for (SamplerKind kind : {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 5, 6.0);
    BatchTracer a(scene, whole, sampler), b(shapes, from_shapes, sampler);
    uint64_t two_sided_hits = 0;
    for (uint32_t id = 0; id < scene.patches.size(); id += 2) {
      const Batch batch{1, id, 100, 700};
      const BatchResult expected = a.Run(batch);
      EXPECT_EQ(b.Run(batch), expected) << SamplerName(kind) << " patch " << id;
      for (const PatchHits& h : expected.hits) two_sided_hits += two_sided[h.patch];
    }
    EXPECT_GT(two_sided_hits, 0u) << SamplerName(kind);  // the two-sided geometry was traced
  }
}

// An agent builds its caster from a stream of the patches before it holds their shapes, which it
// decodes after into room reserved before (agent/prepared_scene.cc): the caster must trace as the
// one built from the whole scene, and refuse a stream that does not give the count it was told.
TEST(RayBlockTest, ACasterStreamedBeforeItsNormalsExistTracesAsTheWholeScene) {
  PatchScene scene = MixedScene();
  for (size_t i = 1; i < scene.patches.size(); i += 3) scene.patches[i].two_sided = true;
  const RayCaster::PatchStream stream = [&scene](const RayCaster::PatchVisitor& each) {
    for (const Patch& p : scene.patches) each(p, p.two_sided);
  };
  std::vector<PatchShape> shapes;
  shapes.reserve(scene.patches.size());
  const Vec3* normals = reinterpret_cast<const Vec3*>(reinterpret_cast<const char*>(shapes.data()) +
                                                      offsetof(PatchShape, normal));
  const RayCaster streamed(scene.patches.size(), stream, normals, sizeof(PatchShape));
  shapes.assign(scene.patches.begin(), scene.patches.end());  // the normals, after the build
  const RayCaster whole(scene);
  ASSERT_EQ(whole.origin_offset(), streamed.origin_offset());
  uint64_t hits = 0;
  for (SamplerKind kind : {SamplerKind::kGrid, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 9, 6.0);
    BatchTracer a(scene, whole, sampler), b(shapes, streamed, sampler);
    for (uint32_t id = 0; id < scene.patches.size(); ++id) {
      const Batch batch{2, id, 0, 600};
      const BatchResult expected = a.Run(batch);
      EXPECT_EQ(b.Run(batch), expected) << SamplerName(kind) << " patch " << id;
      hits += expected.hits.size();
    }
  }
  EXPECT_GT(hits, 0u);
  for (const Patch& p : scene.patches) {  // Trace, which reads a patch's normal on every hit
    const Vec3 d = Normalize(p.normal + Vec3{0.1, 0.2, -0.05});
    const RayHit h = whole.Trace(p.centre, d, p.normal), g = streamed.Trace(p.centre, d, p.normal);
    EXPECT_EQ(g.patch, h.patch);
    EXPECT_EQ(g.front, h.front);
  }
  const RayCaster::PatchStream short_one = [&scene](const RayCaster::PatchVisitor& each) {
    for (size_t i = 1; i < scene.patches.size(); ++i) each(scene.patches[i], false);
  };
  EXPECT_THROW(RayCaster(scene.patches.size(), short_one, normals, sizeof(PatchShape)),
               std::invalid_argument);
}

// A batch's result counted ray by ray from Sample and Trace: what BatchTracer::Run must give, on
// either of its ways to sum the hits (a sorted list up to 256 rays, the dense array beyond).
BatchResult CountRayByRay(const PatchScene& scene, const RayCaster& caster,
                          const RaySampler& sampler, const Batch& batch) {
  const Patch& shooter = scene.patches[batch.shooter];
  const ShotSampler shot =
      sampler.Shot(shooter, batch.shooter, batch.round, caster.origin_offset());
  BatchResult result;
  std::map<uint32_t, uint64_t> weights;
  for (uint32_t k = 0; k < batch.ray_count; ++k) {
    const RaySample ray = shot.Sample(batch.first_ray + k);
    const RayHit hit = caster.Trace(ray.origin, ray.direction, shooter.normal);
    if (hit.patch == RayHit::kMiss) {
      result.escaped_weight += ray.weight;
      ++result.escaped_rays;
    } else if (!hit.front) {
      result.back_weight += ray.weight;
      ++result.back_rays;
    } else {
      weights[hit.patch] += ray.weight;
    }
  }
  for (const auto& [patch, weight] : weights) result.hits.push_back({patch, weight});
  return result;
}

TEST(RayBlockTest, ShortAndLongBatchesSumTheirHitsAsRayByRay) {
  const PatchScene scene = MixedScene();
  const RayCaster caster(scene);
  for (SamplerKind kind : {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 7, 4.0);
    BatchTracer tracer(scene, caster, sampler);
    for (uint32_t id = 0; id < scene.patches.size(); id += 5) {
      // Short and long batches in turn, so each way of summing follows the other's leftovers.
      for (uint32_t rays : {1u, 13u, 256u, 257u, 40u, 1500u, 200u}) {
        const Batch batch{3, id, 11, rays};
        ASSERT_EQ(tracer.Run(batch), CountRayByRay(scene, caster, sampler, batch))
            << SamplerName(kind) << " patch " << id << ", " << rays << " rays";
      }
    }
  }
}

// RunMany traces runs of short batches of different shooters (some two-sided, one tilted), rounds
// and first rays in shared blocks: each result must be the batch's own, ray by ray, whatever its
// neighbours, and long batches between the runs are traced alone as Run traces them.
TEST(RayBlockTest, RunManyGivesEachBatchItsOwnResult) {
  PatchScene scene = MixedScene();
  for (size_t i = 2; i < scene.patches.size(); i += 7) scene.patches[i].two_sided = true;
  const RayCaster caster(scene);
  const auto shooters = static_cast<uint32_t>(scene.patches.size());
  for (SamplerKind kind : {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 5, 4.0);
    BatchTracer many(scene, caster, sampler), one(scene, caster, sampler);
    std::vector<Batch> batches;
    const uint32_t sizes[] = {13, 1, 64, 50, 256, 257, 7, 0, 3, 1500, 200, 16, 17, 100, 63, 65};
    for (uint32_t k = 0; k < 60; ++k) {
      const uint32_t round = k % 5 == 4 ? kGatherRound : k % 3;
      batches.push_back({round, (k * 37) % shooters, uint64_t{k} * 11 % 97, sizes[k % 16]});
    }
    std::vector<BatchResult> results(batches.size());
    results[5].escaped_rays = 99;  // left over from before: RunMany replaces it
    for (size_t begin = 0; begin < batches.size();) {
      const size_t end = BatchTracer::GroupEnd(batches, begin);
      uint64_t rays = 0;
      for (size_t k = begin; k < end; ++k) rays += batches[k].ray_count;
      EXPECT_TRUE(end == begin + 1 || rays <= BatchTracer::kGroupRays) << begin;
      many.RunMany(std::span(batches).subspan(begin, end - begin), results.data() + begin);
      begin = end;
    }
    for (size_t k = 0; k < batches.size(); ++k) {
      ASSERT_EQ(results[k], CountRayByRay(scene, caster, sampler, batches[k]))
          << SamplerName(kind) << " batch " << k << ", " << batches[k].ray_count << " rays";
      ASSERT_EQ(results[k], one.Run(batches[k])) << SamplerName(kind) << " batch " << k;
    }
    // All in one call too: the runs found inside RunMany.
    std::vector<BatchResult> whole(batches.size());
    many.RunMany(batches, whole.data());
    EXPECT_EQ(whole, results) << SamplerName(kind);
  }
}

// A scene of 5,400 patches: a batch of 257-337 rays notes the patches it touches in the dense
// array and sorts them; a longer one (16 rays a patch or more) scans the array; and the array is
// big enough to be prefetched.
TEST(RayBlockTest, MidSizedScenesSumDenseBatchesFromTheTouchedPatchesOrAScan) {
  const PatchScene scene =
      testing::MakeClosedBox({-1, -1, -1}, {1, 2, 3}, 30, {{0.5, 0.5, 0.5}, {}});
  ASSERT_EQ(scene.patches.size(), 5400u);
  const RayCaster caster(scene);
  const RaySampler sampler(SamplerKind::kSobol, 9, 4.0);
  BatchTracer tracer(scene, caster, sampler);
  for (uint32_t id = 0; id < scene.patches.size(); id += 997) {
    for (uint32_t rays : {300u, 2000u, 257u, 337u, 338u, 20u, 5000u, 290u}) {
      const Batch batch{4, id, 3, rays};
      ASSERT_EQ(tracer.Run(batch), CountRayByRay(scene, caster, sampler, batch))
          << "patch " << id << ", " << rays << " rays";
    }
  }
}

// A scene of more than BatchTracer's kDenseMaxPatches (65,536) patches: long batches are summed
// in the hash table, and a batch too long for the table in a dense array made for it alone.
TEST(RayBlockTest, BigScenesSumHashedAndDenseBatchesAsRayByRay) {
  const PatchScene scene =
      testing::MakeClosedBox({-1, -1, -1}, {1, 2, 3}, 105, {{0.5, 0.5, 0.5}, {}});
  ASSERT_GT(scene.patches.size(), size_t{1} << 16);
  const RayCaster caster(scene);
  const RaySampler sampler(SamplerKind::kSobol, 7, 4.0);
  BatchTracer tracer(scene, caster, sampler);
  // 66,150 patches: the table takes batches of up to 11,025 rays; 12,000 go to the dense array.
  for (uint32_t id = 0; id < scene.patches.size(); id += 6007) {
    for (uint32_t rays : {13u, 3000u, 257u, 12000u, 40u, 11025u, 1u}) {
      const Batch batch{2, id, 5, rays};
      ASSERT_EQ(tracer.Run(batch), CountRayByRay(scene, caster, sampler, batch))
          << "patch " << id << ", " << rays << " rays";
    }
  }
}

}  // namespace
}  // namespace radfarm
