// Deterministic jitter: a value in [0, 1) as a pure function of (seed, keys), so a room's furniture
// does not depend on the order rooms are generated in, nor on the standard library (std::
// distributions are implementation-defined).
#pragma once

#include <cstdint>
#include <initializer_list>

namespace radfarm::scenegen {

// SplitMix64's finaliser, folded over the keys.
inline uint64_t MixKeys(uint64_t seed, std::initializer_list<uint64_t> keys) {
  uint64_t h = seed;
  for (uint64_t k : keys) {
    h += 0x9e3779b97f4a7c15ull ^ k;
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    h ^= h >> 31;
  }
  return h;
}

// Uniform in [0, 1) with 53 random bits.
inline double Jitter(uint64_t seed, std::initializer_list<uint64_t> keys) {
  return static_cast<double>(MixKeys(seed, keys) >> 11) * 0x1.0p-53;
}

// Uniform in [lo, hi).
inline double JitterIn(double lo, double hi, uint64_t seed, std::initializer_list<uint64_t> keys) {
  return lo + (hi - lo) * Jitter(seed, keys);
}

}  // namespace radfarm::scenegen
