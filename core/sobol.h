// Randomised Sobol points in 4 dimensions (two for the origin on the patch, two for the direction),
// with random access by index. Written here rather than taken from a library because the solver
// needs O(1) access to point k for any k, so a batch can start anywhere, and a randomisation keyed
// by (seed, round, shooter).
//
// Randomisation: a random digital shift (each coordinate XORed with a per-shot 32-bit key). It
// keeps every power-of-two prefix a (0, m, 2)-net in the first two dimensions. Owen scrambling
// (Burley 2020) gives no lower form-factor error (tests/core/form_factor_test.cc) at several times
// the cost per point, because visibility makes the integrands discontinuous and Owen's faster rate
// needs smooth ones.
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

  // Points first, first + 1, ..., first + count - 1 (indices wrap at 2^32, as Point's do), the same
  // values as Point's, coordinate d of point first + i in u[d][i]. One XOR per coordinate per point
  // instead of one per set bit of the index.
  void Points(uint32_t first, int count, double* const u[kDimensions]) const;

 private:
  std::array<uint32_t, kDimensions> dim_seeds_;
};

}  // namespace radfarm
