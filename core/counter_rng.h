// Counter-based random numbers: a pure function of (key, counter), no state. This is what makes a
// batch's rays depend only on (seed, round, shooter, ray index), wherever and whenever they are
// generated (see batch.h for the determinism contract).
#pragma once

#include <cstdint>

namespace radfarm {

// The SplitMix64 finaliser (Steele et al., "Fast splittable pseudorandom number generators"): a
// bijective avalanche mix of 64 bits.
constexpr uint64_t Mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

// Hash of several words, order-sensitive.
constexpr uint64_t HashWords(uint64_t a, uint64_t b) {
  return Mix64(a ^ Mix64(b + 0x9e3779b97f4a7c15ULL));
}
constexpr uint64_t HashWords(uint64_t a, uint64_t b, uint64_t c) {
  return HashWords(HashWords(a, b), c);
}
constexpr uint64_t HashWords(uint64_t a, uint64_t b, uint64_t c, uint64_t d) {
  return HashWords(HashWords(a, b, c), d);
}

// Uniform double in [0, 1) from the top 53 bits.
constexpr double ToUnitDouble(uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

// Independent uniform numbers for one sample: `Uniform(dim)` is a pure function of (key, dim).
class CounterRng {
 public:
  explicit constexpr CounterRng(uint64_t key) : key_(key) {}
  constexpr double Uniform(uint32_t dim) const { return ToUnitDouble(HashWords(key_, dim)); }

 private:
  uint64_t key_;
};

}  // namespace radfarm
