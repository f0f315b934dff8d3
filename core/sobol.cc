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
constexpr std::array<Polynomial, 3> kPolynomials = {{{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}}};

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

uint32_t SobolCoordinate(uint32_t index, int dim) {
  uint32_t x = 0;
  for (int bit = 0; index != 0; ++bit, index >>= 1) {
    if (index & 1u) x ^= kDirections[dim][bit];
  }
  return x;
}

uint32_t ReverseBits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Laine-Karras style hash that only lets lower bits affect higher ones; on bit-reversed input that
// is a nested uniform scramble (Burley 2020, with his improved constants).
uint32_t LaineKarrasPermutation(uint32_t x, uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

uint32_t NestedUniformScramble(uint32_t x, uint32_t seed) {
  return ReverseBits(LaineKarrasPermutation(ReverseBits(x), seed));
}

}  // namespace

ScrambledSobol4::ScrambledSobol4(uint64_t seed) {
  index_seed_ = static_cast<uint32_t>(HashWords(seed, 0x51));
  for (int d = 0; d < kDimensions; ++d) {
    dim_seeds_[d] = static_cast<uint32_t>(HashWords(seed, 0x100 + d));
  }
}

std::array<double, ScrambledSobol4::kDimensions> ScrambledSobol4::Point(uint32_t index) const {
  // Shuffling the index with an Owen scramble keeps every power-of-two prefix stratified while
  // decorrelating the dimensions' padding (Burley 2020, section 4).
  const uint32_t shuffled = NestedUniformScramble(index, index_seed_);
  std::array<double, kDimensions> p;
  for (int d = 0; d < kDimensions; ++d) {
    const uint32_t x = NestedUniformScramble(SobolCoordinate(shuffled, d), dim_seeds_[d]);
    p[d] = double(x) * 0x1.0p-32;
  }
  return p;
}

}  // namespace radfarm
