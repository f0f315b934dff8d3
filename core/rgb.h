// RGB triple for reflectance, emission and radiosity. The solver is linear in each channel.
#pragma once

#include <cmath>

namespace radfarm {

struct Rgb {
  double r = 0, g = 0, b = 0;

  constexpr Rgb() = default;
  constexpr Rgb(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}

  constexpr Rgb operator+(const Rgb& o) const { return {r + o.r, g + o.g, b + o.b}; }
  constexpr Rgb operator-(const Rgb& o) const { return {r - o.r, g - o.g, b - o.b}; }
  constexpr Rgb operator*(const Rgb& o) const { return {r * o.r, g * o.g, b * o.b}; }
  constexpr Rgb operator*(double s) const { return {r * s, g * s, b * s}; }
  constexpr Rgb operator/(double s) const { return {r / s, g / s, b / s}; }
  constexpr Rgb& operator+=(const Rgb& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  constexpr bool operator==(const Rgb& o) const = default;

  // Sum of the channels: the scalar "power" used to rank shooters and measure convergence.
  constexpr double Sum() const { return r + g + b; }
  // Sum of the channels' magnitudes: the size of an unshot radiosity that may be negative
  // (over-relaxation). Equals Sum() when no channel is negative.
  constexpr double AbsSum() const { return (r < 0 ? -r : r) + (g < 0 ? -g : g) + (b < 0 ? -b : b); }
  constexpr double Max() const { return r > g ? (r > b ? r : b) : (g > b ? g : b); }
  constexpr double Min() const { return r < g ? (r < b ? r : b) : (g < b ? g : b); }
  bool IsFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr Rgb operator*(double s, const Rgb& c) { return c * s; }

}  // namespace radfarm
