#include "core/point_gather.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/counter_rng.h"
#include "core/ray_sampler.h"
#include "core/sobol.h"
#include "core/thread_pool.h"
#include "core/vec3.h"

namespace radfarm {
namespace {

// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 ClosestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

struct NearQuery {
  const PatchScene* scene;
  const RayCaster* caster;
  Vec3 point, normal;
  double radius, plane_tolerance;
  bool found = false;
};

// Embree calls this for each triangle whose box meets the query's sphere.
bool VisitNearTriangle(RTCPointQueryFunctionArguments* args) {
  NearQuery& q = *static_cast<NearQuery*>(args->userPtr);
  const Patch& p = q.scene->patches[q.caster->PatchOf(args->geomID, args->primID)];
  // The point's own plane (its surface, or one flush with it) hides nothing from it.
  if (std::fabs(Dot(p.normal, q.normal)) > 1 - 1e-9 &&
      std::fabs(Dot(p.centre - q.point, q.normal)) <= q.plane_tolerance) {
    return false;
  }
  for (int t = 0; t + 2 < p.corner_count; ++t) {
    const Vec3 closest =
        ClosestOnTriangle(q.point, p.corners[0], p.corners[t + 1], p.corners[t + 2]);
    const Vec3 to = closest - q.point;
    if (Length(to) <= q.radius && Dot(to, q.normal) >= -q.plane_tolerance) {
      q.found = true;
      args->query->radius = 0;  // nothing more to learn
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<bool> NearOtherSurfaces(const PatchScene& scene, const RayCaster& caster,
                                    const std::vector<ReceiverPoint>& points, double radius,
                                    unsigned threads) {
  std::vector<bool> out(points.size(), false);
  if (points.empty() || !(radius > 0)) return out;
  std::vector<uint8_t> near(points.size(), 0);  // vector<bool> is not safe to write in parallel
  ThreadPool pool(threads);
  // Embree's query is in float: its sphere is grown by a hair and each candidate is tested again
  // in double here.
  const double tolerance = 4 * caster.origin_offset();
  pool.ParallelFor(points.size(), [&](unsigned, size_t i) {
    NearQuery q{&scene, &caster, points[i].position, points[i].normal, radius, tolerance};
    const Vec3 at = points[i].position - caster.centre();
    RTCPointQuery query;
    query.x = float(at.x);
    query.y = float(at.y);
    query.z = float(at.z);
    query.time = 0;
    query.radius = float(radius * (1 + 1e-5) + tolerance);
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(caster.embree_scene(), &query, &context, VisitNearTriangle, &q);
    near[i] = q.found;
  });
  for (size_t i = 0; i < points.size(); ++i) out[i] = near[i] != 0;
  return out;
}

Rgb InterpolateCornerOffsets(const Patch& p, const std::array<Rgb, 4>& offsets, const Vec3& x) {
  // A quad's triangle: (0, 1, 2) on corner 1's side of the diagonal 0-2, else (0, 2, 3).
  const Vec3& a = p.corners[0];
  int j = 1, k = 2;
  if (p.corner_count == 4 && Dot(Cross(p.corners[2] - a, x - a), p.normal) > 0) j = 2, k = 3;
  // Barycentric weights in it, clamped so a hit a hair outside (rounding) stays bounded.
  const Vec3 e1 = p.corners[j] - a, e2 = p.corners[k] - a, d = x - a;
  const Vec3 n = Cross(e1, e2);
  const double n2 = Dot(n, n);
  if (!(n2 > 0)) return {};
  const double wj = std::max(0.0, Dot(Cross(d, e2), n) / n2);
  const double wk = std::max(0.0, Dot(Cross(e1, d), n) / n2);
  const double wa = std::max(0.0, 1 - wj - wk), total = wa + wj + wk;
  return (offsets[0] * wa + offsets[j] * wj + offsets[k] * wk) * (1 / total);
}

std::vector<Rgb> GatherLight(const RayCaster& caster, const std::vector<Rgb>& outgoing,
                             const std::vector<ReceiverPoint>& points,
                             const std::vector<bool>& gather, uint64_t seed, unsigned threads,
                             uint32_t rays, const PatchCornerOffsets* corners,
                             const SecondBounce* second, uint64_t* rays_cast,
                             uint64_t first_index) {
  std::vector<Rgb> out(points.size());
  if (points.empty() || rays == 0) return out;
  ThreadPool pool(threads);
  // Stream constant: keeps these keys apart from every other use of the seed.
  const uint64_t stream = HashWords(seed, 0x6761746865726eull);
  const PatchScene* scene = corners != nullptr ? corners->scene : nullptr;
  if (second != nullptr) scene = second->scene;
  // Where a ray from `origin` along `d` meets patch f's plane (false when it runs along it).
  const auto meet = [&](uint32_t f, const Vec3& origin, const Vec3& d, Vec3* at, double* distance) {
    const Patch& p = scene->patches[f];
    const double cos = Dot(d, p.normal);
    if (!(std::fabs(cos) > 1e-12)) return false;
    *distance = Dot(p.corners[0] - origin, p.normal) / cos;
    *at = origin + d * *distance;
    return true;
  };
  std::vector<uint64_t> seconds_cast(pool.size(), 0);  // per worker: the same sum in any order
  pool.ParallelFor(points.size(), [&](unsigned worker, size_t i) {
    if (!gather[i]) return;
    const ReceiverPoint& point = points[i];
    uint64_t second_rays = 0;
    Vec3 t, b;
    OrthonormalBasis(point.normal, &t, &b);
    const ScrambledSobol4 sobol(HashWords(stream, first_index + i));
    Rgb sum;
    // The rays a block at a time (RayCaster::TraceBlock: the same hits as Trace's, their cache
    // misses overlapped), counted in order.
    RayBlock block;
    RayHit hits[RayBlock::kSize];
    std::array<double, 2> second_u[RayBlock::kSize];
    for (uint32_t first = 0; first < rays; first += RayBlock::kSize) {
      block.count = int(std::min<uint32_t>(RayBlock::kSize, rays - first));
      for (int j = 0; j < block.count; ++j) {
        const std::array<double, 4> u = sobol.Point(first + uint32_t(j));
        const Vec3 d = SampleCosineDirection(t, b, point.normal, u[0], u[1]);
        block.origin_x[j] = point.position.x;
        block.origin_y[j] = point.position.y;
        block.origin_z[j] = point.position.z;
        block.direction_x[j] = d.x;
        block.direction_y[j] = d.y;
        block.direction_z[j] = d.z;
        second_u[j] = {u[2], u[3]};
      }
      caster.TraceBlock(block, point.normal, hits);
      for (int j = 0; j < block.count; ++j) {
        const RayHit& hit = hits[j];
        if (hit.patch == RayHit::kMiss || !hit.front) continue;
        sum += outgoing[hit.patch];
        if (scene == nullptr) continue;
        const Vec3 d{block.direction_x[j], block.direction_y[j], block.direction_z[j]};
        Vec3 at;
        double distance;
        if (!meet(hit.patch, point.position, d, &at, &distance)) continue;
        const Patch& p = scene->patches[hit.patch];
        if (corners != nullptr) {
          sum += InterpolateCornerOffsets(p, corners->offsets[hit.patch], at);
        }
        if (second == nullptr || !(distance < second->reach * std::sqrt(p.area))) continue;
        // The patch's mean bounced light gives way to one ray's worth gathered at the hit, along
        // the Sobol point's two other dimensions.
        Vec3 t2, b2;
        OrthonormalBasis(p.normal, &t2, &b2);
        const Vec3 d2 = SampleCosineDirection(t2, b2, p.normal, second_u[j][0], second_u[j][1]);
        const RayHit hit2 = caster.Trace(at, d2, p.normal);
        ++second_rays;
        Rgb gathered;
        Vec3 at2;
        double distance2;
        if (hit2.patch != RayHit::kMiss && hit2.front) {
          gathered = outgoing[hit2.patch];
          if (corners != nullptr && meet(hit2.patch, at, d2, &at2, &distance2)) {
            gathered += InterpolateCornerOffsets(scene->patches[hit2.patch],
                                                 corners->offsets[hit2.patch], at2);
          }
        }
        sum += p.reflectance * gathered - second->bounced[hit.patch];
      }
    }
    out[i] = sum / double(rays);
    seconds_cast[worker] += second_rays;
  });
  if (rays_cast != nullptr) {
    *rays_cast += uint64_t(std::count(gather.begin(), gather.end(), true)) * rays;
    for (uint64_t c : seconds_cast) *rays_cast += c;
  }
  return out;
}

}  // namespace radfarm
