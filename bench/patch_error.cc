#include "bench/patch_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace radfarm::bench {

ErrorPatches ClassifyPatches(const std::vector<Rgb>& reference) {
  ErrorPatches out;
  std::vector<double> positive;
  for (uint32_t i = 0; i < reference.size(); ++i) {
    if (reference[i].Sum() > 0) {
      out.all.push_back(i);
      positive.push_back(reference[i].Sum());
    }
  }
  if (positive.empty()) return out;
  std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
  const double threshold = kDarkFraction * positive[positive.size() / 2];
  for (uint32_t i : out.all) {
    if (reference[i].Sum() >= threshold) out.lit.push_back(i);
  }
  return out;
}

double RmsRelativeError(const std::vector<Rgb>& radiosity, const std::vector<Rgb>& reference,
                        const std::vector<uint32_t>& patches) {
  if (radiosity.size() != reference.size()) {
    throw std::invalid_argument("RmsRelativeError: solutions of different sizes");
  }
  if (patches.empty()) return 0;
  double sum = 0;
  for (uint32_t i : patches) {
    const double ref = reference[i].Sum();
    const double rel = (radiosity[i].Sum() - ref) / ref;
    sum += rel * rel;
  }
  return std::sqrt(sum / double(patches.size()));
}

}  // namespace radfarm::bench
