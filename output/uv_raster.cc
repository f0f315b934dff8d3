#include "output/uv_raster.h"

#include <algorithm>
#include <cmath>

namespace radfarm {
namespace {

constexpr int64_t kSub = 256;  // fixed-point steps per texel
// Texels: UVs far outside the image are clamped, so edge products (2^29 squared) fit in 64 bits.
constexpr double kLimit = double(1 << 20);

int64_t FloorDiv(int64_t a, int64_t b) { return a / b - (a % b != 0 && (a < 0) != (b < 0)); }

struct Point {
  int64_t x, y;
};

// Twice the signed area of (a, b, p): positive when p is left of a->b in a y-up frame.
int64_t Edge(const Point& a, const Point& b, const Point& p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// The top-left rule for a triangle of positive Edge(a, b, c): an edge owns the centres on it when
// it is a top edge (horizontal, the inside below it in image rows) or a left edge.
bool OwnsEdge(const Point& a, const Point& b) {
  const int64_t dx = b.x - a.x, dy = b.y - a.y;
  return dy < 0 || (dy == 0 && dx > 0);
}

using Point2 = std::array<double, 2>;

// Twice the signed area of (a, b, p), as Edge in texels.
double Cross2(const Point2& a, const Point2& b, const Point2& p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

// The Chebyshev (L-infinity) distance from p to the segment a-b: max(|dx|, |dy|) is convex and
// piecewise linear along the segment, so its least is at an end or where |dx| = |dy|.
double DistanceToSegment(const Point2& a, const Point2& b, const Point2& p) {
  const double ax = a[0] - p[0], ay = a[1] - p[1], dx = b[0] - a[0], dy = b[1] - a[1];
  const auto at = [&](double s) { return std::max(std::abs(ax + s * dx), std::abs(ay + s * dy)); };
  double best = std::min(at(0), at(1));
  // ax + s dx = ay + s dy, and ax + s dx = -(ay + s dy).
  for (const double denominator : {dx - dy, dx + dy}) {
    if (denominator == 0) continue;
    const double s = (denominator == dx - dy ? ay - ax : -ay - ax) / denominator;
    if (s > 0 && s < 1) best = std::min(best, at(s));
  }
  return best;
}

// From p to the counter-clockwise triangle t, Chebyshev: 0 inside.
double DistanceToTriangle(const std::array<Point2, 3>& t, const Point2& p) {
  if (Cross2(t[0], t[1], p) >= 0 && Cross2(t[1], t[2], p) >= 0 && Cross2(t[2], t[0], p) >= 0) {
    return 0;
  }
  return std::min({DistanceToSegment(t[0], t[1], p), DistanceToSegment(t[1], t[2], p),
                   DistanceToSegment(t[2], t[0], p)});
}

}  // namespace

UvRaster::UvRaster(uint32_t width, uint32_t height) {
  image_.width = width;
  image_.height = height;
  image_.pixels.assign(size_t{width} * height, Rgb{});
  state_.assign(image_.pixels.size(), kEmpty);
}

void UvRaster::Draw(const std::array<Uv, 3>& uv, const std::array<Rgb, 3>& value) {
  ++stats_.triangles;
  std::array<Point, 3> p{};
  for (int k = 0; k < 3; ++k) {
    const double x = double(uv[k][0]) * image_.width, y = double(uv[k][1]) * image_.height;
    if (!std::isfinite(x) || !std::isfinite(y)) {
      ++stats_.degenerate;
      return;
    }
    p[k] = {std::llround(std::clamp(x, -kLimit, kLimit) * kSub),
            std::llround(std::clamp(y, -kLimit, kLimit) * kSub)};
  }
  int64_t area = Edge(p[0], p[1], p[2]);
  std::array<Rgb, 3> v = value;
  if (area < 0) {  // either winding: mirrored UV islands are as valid as others
    std::swap(p[1], p[2]);
    std::swap(v[1], v[2]);
    area = -area;
  }
  if (area == 0) {
    ++stats_.degenerate;
    return;
  }
  Drawn& drawn = drawn_.emplace_back();
  for (int k = 0; k < 3; ++k) drawn.at[k] = {double(p[k].x) / kSub, double(p[k].y) / kSub};
  drawn.value = v;
  const auto texel_range = [](int64_t lo, int64_t hi, uint32_t size) {
    // The texels whose centres, (i + 0.5) * kSub, lie within [lo, hi].
    const int64_t first = -FloorDiv(kSub / 2 - lo, kSub);
    const int64_t last = FloorDiv(hi - kSub / 2, kSub);
    return std::pair{std::max<int64_t>(first, 0), std::min<int64_t>(last, int64_t{size} - 1)};
  };
  const auto [x0, x1] = texel_range(std::min({p[0].x, p[1].x, p[2].x}),
                                    std::max({p[0].x, p[1].x, p[2].x}), image_.width);
  const auto [y0, y1] = texel_range(std::min({p[0].y, p[1].y, p[2].y}),
                                    std::max({p[0].y, p[1].y, p[2].y}), image_.height);
  const bool own0 = OwnsEdge(p[1], p[2]), own1 = OwnsEdge(p[2], p[0]), own2 = OwnsEdge(p[0], p[1]);
  for (int64_t y = y0; y <= y1; ++y) {
    for (int64_t x = x0; x <= x1; ++x) {
      const Point c{x * kSub + kSub / 2, y * kSub + kSub / 2};
      const int64_t w0 = Edge(p[1], p[2], c), w1 = Edge(p[2], p[0], c), w2 = Edge(p[0], p[1], c);
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      if ((w0 == 0 && !own0) || (w1 == 0 && !own1) || (w2 == 0 && !own2)) continue;
      const size_t i = Index(static_cast<uint32_t>(x), static_cast<uint32_t>(y));
      if (state_[i] != kEmpty) {
        ++stats_.overlapped;
        continue;
      }
      const double a = double(area);
      image_.pixels[i] =
          v[0] * (double(w0) / a) + v[1] * (double(w1) / a) + v[2] * (double(w2) / a);
      state_[i] = kDrawn;
      ++stats_.covered;
    }
  }
}

void UvRaster::Extend(double reach) {
  std::vector<double> nearest(state_.size(), INFINITY);
  for (const Drawn& t : drawn_) {
    // References, not a structured binding: the lambda below captures them, which clang 14
    // refuses for a binding.
    const std::array<double, 2>&a = t.at[0], &b = t.at[1], &c = t.at[2];
    const double area = Cross2(a, b, c);
    const auto range = [&](int axis, uint32_t size) {
      const double lo = std::min({a[axis], b[axis], c[axis]}) - reach - 0.5;
      const double hi = std::max({a[axis], b[axis], c[axis]}) + reach - 0.5;
      return std::pair{int64_t(std::max(std::ceil(lo), 0.0)),
                       int64_t(std::min(std::floor(hi), double(size) - 1))};
    };
    const auto [x0, x1] = range(0, image_.width);
    const auto [y0, y1] = range(1, image_.height);
    for (int64_t y = y0; y <= y1; ++y) {
      for (int64_t x = x0; x <= x1; ++x) {
        const size_t i = Index(uint32_t(x), uint32_t(y));
        if (state_[i] == kDrawn) continue;
        const Point2 p{double(x) + 0.5, double(y) + 0.5};
        const double d = DistanceToTriangle(t.at, p);
        if (!(d <= reach) || !(d < nearest[i])) continue;
        nearest[i] = d;
        // Barycentric coordinates, negative outside: the triangle's linear function extended.
        const double w0 = Cross2(b, c, p) / area, w1 = Cross2(c, a, p) / area;
        const Rgb value = t.value[0] * w0 + t.value[1] * w1 + t.value[2] * (1 - w0 - w1);
        image_.pixels[i] =
            Rgb(std::max(value.r, 0.0), std::max(value.g, 0.0), std::max(value.b, 0.0));
        if (state_[i] == kEmpty) ++stats_.extended;
        state_[i] = kExtended;
      }
    }
  }
}

void UvRaster::Fit(const std::vector<Sample>& samples, int passes) {
  const int64_t w = image_.width, h = image_.height;
  for (int pass = 0; pass < passes; ++pass) {
    for (const Sample& s : samples) {
      const double x = double(s.uv[0]) * w - 0.5, y = double(s.uv[1]) * h - 0.5;
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      const int64_t x0 = int64_t(std::floor(x)), y0 = int64_t(std::floor(y));
      const double fx = x - double(x0), fy = y - double(y0);
      const std::array<double, 4> weight = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy,
                                            fx * fy};
      std::array<int64_t, 4> at{};
      Rgb read;
      double free_weight = 0;  // sum of the squared weights of the texels Fit may move
      for (int k = 0; k < 4; ++k) {
        const int64_t tx = x0 + (k & 1), ty = y0 + (k >> 1);
        at[k] = tx < 0 || ty < 0 || tx >= w || ty >= h ? -1
                                                       : int64_t(Index(uint32_t(tx), uint32_t(ty)));
        if (at[k] < 0) continue;
        read += image_.pixels[size_t(at[k])] * weight[k];
        if (state_[size_t(at[k])] == kExtended) free_weight += weight[k] * weight[k];
      }
      if (free_weight < 1e-6) continue;
      const Rgb step = (s.value - read) / free_weight;
      for (int k = 0; k < 4; ++k) {
        if (at[k] < 0 || state_[size_t(at[k])] != kExtended) continue;
        Rgb& texel = image_.pixels[size_t(at[k])];
        texel = texel + step * weight[k];
        texel = Rgb(std::max(texel.r, 0.0), std::max(texel.g, 0.0), std::max(texel.b, 0.0));
      }
    }
  }
}

void UvRaster::Dilate(int texels) {
  const int64_t w = image_.width, h = image_.height;
  std::vector<size_t> fill;
  std::vector<Rgb> values;
  for (int pass = 0; pass < texels; ++pass) {
    fill.clear();
    values.clear();
    for (int64_t y = 0; y < h; ++y) {
      for (int64_t x = 0; x < w; ++x) {
        if (state_[Index(uint32_t(x), uint32_t(y))] != kEmpty) continue;
        Rgb sum;
        int n = 0;
        for (int64_t dy = -1; dy <= 1; ++dy) {
          for (int64_t dx = -1; dx <= 1; ++dx) {
            const int64_t nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            const size_t j = Index(uint32_t(nx), uint32_t(ny));
            if (state_[j] == kEmpty) continue;
            sum += image_.pixels[j];
            ++n;
          }
        }
        if (n == 0) continue;
        fill.push_back(Index(uint32_t(x), uint32_t(y)));
        values.push_back(sum / n);
      }
    }
    if (fill.empty()) return;
    for (size_t k = 0; k < fill.size(); ++k) {
      image_.pixels[fill[k]] = values[k];
      state_[fill[k]] = kDilated;
    }
    stats_.dilated += fill.size();
  }
}

}  // namespace radfarm
