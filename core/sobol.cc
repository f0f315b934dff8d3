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

constexpr DirectionTable kDirections = MakeDirections();

// kPrefixXor[d][j] = kDirections[d][0] ^ ... ^ kDirections[d][j]: going from index k to k + 1
// flips bits 0..ctz(k + 1) of the index, so the point's bits change by this prefix.
constexpr DirectionTable MakePrefixXor() {
  DirectionTable p = kDirections;
  for (auto& dim : p) {
    for (int k = 1; k < 32; ++k) dim[k] ^= dim[k - 1];
  }
  return p;
}

constexpr DirectionTable kPrefixXor = MakePrefixXor();

// The unscrambled bits of point `index`: the XOR of the direction numbers of its set bits.
std::array<uint32_t, ScrambledSobol4::kDimensions> PointBits(uint32_t index) {
  static_assert(ScrambledSobol4::kDimensions == 4);
  uint32_t x0 = 0, x1 = 0, x2 = 0, x3 = 0;  // registers, not an array: this loop is hot
  for (uint32_t bits = index; bits != 0; bits &= bits - 1) {
    const int bit = __builtin_ctz(bits);
    x0 ^= kDirections[0][bit];
    x1 ^= kDirections[1][bit];
    x2 ^= kDirections[2][bit];
    x3 ^= kDirections[3][bit];
  }
  return {x0, x1, x2, x3};
}

}  // namespace

ScrambledSobol4::ScrambledSobol4(uint64_t seed) {
  for (int d = 0; d < kDimensions; ++d) {
    dim_seeds_[d] = static_cast<uint32_t>(HashWords(seed, 0x100 + d));
  }
}

std::array<double, ScrambledSobol4::kDimensions> ScrambledSobol4::Point(uint32_t index) const {
  const auto x = PointBits(index);
  return {double(x[0] ^ dim_seeds_[0]) * 0x1.0p-32, double(x[1] ^ dim_seeds_[1]) * 0x1.0p-32,
          double(x[2] ^ dim_seeds_[2]) * 0x1.0p-32, double(x[3] ^ dim_seeds_[3]) * 0x1.0p-32};
}

void ScrambledSobol4::Points(uint32_t first, int count, double* const u[kDimensions]) const {
  auto x = PointBits(first);
  for (int i = 0; i < count; ++i) {
    for (int d = 0; d < kDimensions; ++d) u[d][i] = double(x[d] ^ dim_seeds_[d]) * 0x1.0p-32;
    const uint32_t next = first + static_cast<uint32_t>(i) + 1;
    const int flipped = next == 0 ? 31 : __builtin_ctz(next);  // 2^32 wraps to 0: all bits clear
    for (int d = 0; d < kDimensions; ++d) x[d] ^= kPrefixXor[d][flipped];
  }
}

}  // namespace radfarm
