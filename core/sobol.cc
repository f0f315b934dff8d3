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

// Direction numbers stored bit-reversed: the XOR of reversed numbers is the reversed coordinate,
// which is the form the Owen scramble below wants, so one reversal per coordinate is saved.
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

// Same scramble for an input given already bit-reversed.
uint32_t NestedUniformScrambleReversed(uint32_t reversed_x, uint32_t seed) {
  return ReverseBits(LaineKarrasPermutation(reversed_x, seed));
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
  static_assert(kDimensions == 4);
  uint32_t x0 = 0, x1 = 0, x2 = 0, x3 = 0;  // registers, not an array: this loop is hot
  for (uint32_t bits = shuffled; bits != 0; bits &= bits - 1) {
    const int bit = __builtin_ctz(bits);
    x0 ^= kReversedDirections[0][bit];
    x1 ^= kReversedDirections[1][bit];
    x2 ^= kReversedDirections[2][bit];
    x3 ^= kReversedDirections[3][bit];
  }
  return {double(NestedUniformScrambleReversed(x0, dim_seeds_[0])) * 0x1.0p-32,
          double(NestedUniformScrambleReversed(x1, dim_seeds_[1])) * 0x1.0p-32,
          double(NestedUniformScrambleReversed(x2, dim_seeds_[2])) * 0x1.0p-32,
          double(NestedUniformScrambleReversed(x3, dim_seeds_[3])) * 0x1.0p-32};
}

}  // namespace radfarm
