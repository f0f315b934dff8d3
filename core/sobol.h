// Owen-scrambled Sobol points in 4 dimensions (two for the origin on the patch, two for the
// direction), with random access by index. Written here rather than taken from a library because
// the solver needs (a) O(1) access to point k for any k, so a batch can start anywhere, and (b)
// nested-uniform (Owen) scrambling keyed by (seed, round, shooter); Boost's sobol offers neither.
// Scrambling: the hash-based scheme of Burley, "Practical Hash-based Owen Scrambling", JCGT 2020.
#pragma once

#include <array>
#include <cstdint>

namespace radfarm {

class ScrambledSobol4 {
 public:
  static constexpr int kDimensions = 4;

  // `seed` selects one independent scrambling of the whole sequence.
  explicit ScrambledSobol4(uint64_t seed);

  // The index-th point, each coordinate in [0, 1).
  std::array<double, kDimensions> Point(uint32_t index) const;

 private:
  std::array<uint32_t, kDimensions> dim_seeds_;
  uint32_t index_seed_;
};

}  // namespace radfarm
