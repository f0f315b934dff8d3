#include "mesh/ear_clip.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace radfarm {
namespace {

// Scale of the polygon, for the tolerance of the orientation tests.
double Extent(const std::vector<Point2>& p) {
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (const Point2& q : p) {
    lo_x = std::min(lo_x, q.x);
    lo_y = std::min(lo_y, q.y);
    hi_x = std::max(hi_x, q.x);
    hi_y = std::max(hi_y, q.y);
  }
  return std::max(hi_x - lo_x, hi_y - lo_y);
}

// 1 for an equilateral triangle, towards 0 for slivers.
double Shape(const Point2& a, const Point2& b, const Point2& c) {
  auto sq = [](const Point2& u, const Point2& v) {
    return (u.x - v.x) * (u.x - v.x) + (u.y - v.y) * (u.y - v.y);
  };
  const double edges = sq(a, b) + sq(b, c) + sq(c, a);
  return edges > 0 ? 2.0 * std::sqrt(3.0) * Orient2(a, b, c) / edges : 0.0;
}

bool SamePoint(const Point2& a, const Point2& b) { return a.x == b.x && a.y == b.y; }

class Clipper {
 public:
  explicit Clipper(const std::vector<Point2>& p) : p_(p) {
    const double extent = Extent(p);
    eps_ = 1e-12 * extent * extent;
    for (uint32_t i = 0; i < p.size(); ++i) ring_.push_back(i);
  }

  EarClipResult Run() {
    EarClipResult result;
    while (ring_.size() > 3) {
      size_t ear = BestEar();
      if (ear == kNone) {
        result.simple = false;
        ear = MostConvexCorner();
      }
      result.triangles.push_back({Prev(ear), ring_[ear], Next(ear)});
      ring_.erase(ring_.begin() + static_cast<std::ptrdiff_t>(ear));
    }
    if (ring_.size() == 3 && Orient2(p_[ring_[0]], p_[ring_[1]], p_[ring_[2]]) > eps_) {
      result.triangles.push_back({ring_[0], ring_[1], ring_[2]});
    }
    return result;
  }

 private:
  static constexpr size_t kNone = ~size_t{0};

  uint32_t Prev(size_t k) const { return ring_[(k + ring_.size() - 1) % ring_.size()]; }
  uint32_t Next(size_t k) const { return ring_[(k + 1) % ring_.size()]; }

  size_t BestEar() const {
    const bool first_only = p_.size() > kBestEarLimit;
    size_t best = kNone;
    double best_shape = -1;
    for (size_t k = 0; k < ring_.size(); ++k) {
      if (!IsEar(k)) continue;
      if (first_only) return k;
      const double shape = Shape(p_[Prev(k)], p_[ring_[k]], p_[Next(k)]);
      if (shape > best_shape) {
        best = k;
        best_shape = shape;
      }
    }
    return best;
  }

  // A strictly convex corner whose triangle holds no other corner, not even on its boundary
  // (a corner on the new diagonal would leave a zero-area piece); corners coinciding with the
  // triangle's own (the two ends of a bridge) do not count.
  bool IsEar(size_t k) const {
    const Point2& a = p_[Prev(k)];
    const Point2& b = p_[ring_[k]];
    const Point2& c = p_[Next(k)];
    if (Orient2(a, b, c) <= eps_) return false;
    for (uint32_t i : ring_) {
      const Point2& q = p_[i];
      if (SamePoint(q, a) || SamePoint(q, b) || SamePoint(q, c)) continue;
      if (Orient2(a, b, q) >= -eps_ && Orient2(b, c, q) >= -eps_ && Orient2(c, a, q) >= -eps_) {
        return false;
      }
    }
    return true;
  }

  size_t MostConvexCorner() const {
    size_t best = 0;
    double best_turn = -INFINITY;
    for (size_t k = 0; k < ring_.size(); ++k) {
      const double turn = Orient2(p_[Prev(k)], p_[ring_[k]], p_[Next(k)]);
      if (turn > best_turn) {
        best = k;
        best_turn = turn;
      }
    }
    return best;
  }

  const std::vector<Point2>& p_;
  double eps_ = 0;
  std::vector<uint32_t> ring_;
};

}  // namespace

EarClipResult EarClip(const std::vector<Point2>& polygon) {
  if (polygon.size() < 3) return {};
  return Clipper(polygon).Run();
}

}  // namespace radfarm
