#include "core/sobol.h"

#include "core/counter_rng.h"

namespace radfarm {
namespace {

// Direction numbers for the first four Sobol dimensions (Joe & Kuo, new-joe-kuo-6.21201):
// dimension 1 is van der Corput; the others come from primitive polynomials of degree s with
// coefficients a and initial values m.
struct Polynomial {
  int s;
  uint32_t a;
  std::array<uint32_t, 3> m;
};
constexpr std::array<Polynomial, 3> kPolynomials = {
    {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}}};

using DirectionTable = std::array<std::array<uint32_t, 32>, ScrambledSobol4::kDimensions>;

constexpr DirectionTable MakeDirections() {
  DirectionTable v{};
  for (int k = 0; k < 32; ++k) v[0][k] = 1u << (31 - k);
  for (int d = 1; d < ScrambledSobol4::kDimensions; ++d) {
    const Polynomial& p = kPolynomials[d - 1];
    for (int k = 0; k < 32; ++k) {
      if (k < p.s) {
        v[d][k] = p.m[k] << (31 - k);
        continue;
      }
      uint32_t x = v[d][k - p.s] ^ (v[d][k - p.s] >> p.s);
      for (int j = 1; j < p.s; ++j) {
        if ((p.a >> (p.s - 1 - j)) & 1u) x ^= v[d][k - j];
      }
      v[d][k] = x;
    }
  }
  return v;
}

// Direction numbers stored bit-reversed (bit k of the table is the coefficient of 2^-(k+1)).
constexpr DirectionTable MakeReversedDirections() {
  DirectionTable v = MakeDirections();
  for (auto& dim : v) {
    for (uint32_t& x : dim) {
      uint32_t r = 0;
      for (int bit = 0; bit < 32; ++bit) r |= ((x >> bit) & 1u) << (31 - bit);
      x = r;
    }
  }
  return v;
}

constexpr DirectionTable kReversedDirections = MakeReversedDirections();

inline uint32_t ReverseBits(uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
}

}  // namespace

ScrambledSobol4::ScrambledSobol4(uint64_t seed) {
  for (int d = 0; d < kDimensions; ++d) {
    dim_seeds_[d] = static_cast<uint32_t>(HashWords(seed, 0x100 + d));
  }
}

std::array<double, ScrambledSobol4::kDimensions> ScrambledSobol4::Point(uint32_t index) const {
  static_assert(kDimensions == 4);
  uint32_t x0 = 0, x1 = 0, x2 = 0, x3 = 0;  // registers, not an array: this loop is hot
  for (uint32_t bits = index; bits != 0; bits &= bits - 1) {
    const int bit = __builtin_ctz(bits);
    x0 ^= kReversedDirections[0][bit];
    x1 ^= kReversedDirections[1][bit];
    x2 ^= kReversedDirections[2][bit];
    x3 ^= kReversedDirections[3][bit];
  }
  // The table is bit-reversed, so reverse back before the digital shift.
  return {double(ReverseBits(x0) ^ dim_seeds_[0]) * 0x1.0p-32,
          double(ReverseBits(x1) ^ dim_seeds_[1]) * 0x1.0p-32,
          double(ReverseBits(x2) ^ dim_seeds_[2]) * 0x1.0p-32,
          double(ReverseBits(x3) ^ dim_seeds_[3]) * 0x1.0p-32};
}

}  // namespace radfarm
