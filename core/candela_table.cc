#include "core/candela_table.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace radfarm {
namespace {

bool StrictlyIncreasing(const std::vector<double>& v) {
  for (size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return false;
    if (i > 0 && !(v[i] > v[i - 1])) return false;
  }
  return true;
}

// phi in [0, 360) folded into the range the table's symmetry measured.
double FoldPhi(const std::vector<double>& horizontal, double phi) {
  const double first = horizontal.front();
  const double last = horizontal.back();
  if (horizontal.size() == 1) return first;
  if (first == 90) return phi < 90 || phi > 270 ? std::fmod(540 - phi, 360) : phi;
  if (last == 90) {
    if (phi > 180) phi = 360 - phi;
    return phi > 90 ? 180 - phi : phi;
  }
  if (last == 180) return phi > 180 ? 360 - phi : phi;
  return phi;
}

// Index i and weight t with x between angles[i] and angles[i + 1] (t = 0 on angles[i]); false
// when x lies outside the angles.
bool Bracket(const std::vector<double>& angles, double x, size_t* i, double* t) {
  if (x < angles.front() || x > angles.back()) return false;
  if (angles.size() == 1) {
    *i = 0;
    *t = 0;
    return true;
  }
  const auto upper = std::upper_bound(angles.begin(), angles.end(), x);
  size_t j = static_cast<size_t>(upper - angles.begin());
  j = std::clamp<size_t>(j, 1, angles.size() - 1);
  *i = j - 1;
  *t = (x - angles[j - 1]) / (angles[j] - angles[j - 1]);
  return true;
}

// The table's intensity along one of its horizontal planes, by vertical angle.
double PlaneAt(const CandelaTable& table, size_t h, double theta) {
  size_t v = 0;
  double t = 0;
  if (!Bracket(table.vertical, theta, &v, &t)) return 0;
  const size_t n = table.vertical.size();
  const double a = table.candela[h * n + v];
  if (t == 0) return a;
  return a + (table.candela[h * n + v + 1] - a) * t;
}

}  // namespace

std::string CandelaTableProblem(const CandelaTable& table) {
  const std::vector<double>& v = table.vertical;
  const std::vector<double>& h = table.horizontal;
  if (v.empty() || h.empty()) return "the table has no vertical or no horizontal angles";
  if (!StrictlyIncreasing(v)) return "the vertical angles are not strictly increasing";
  if (v.front() < 0 || v.back() > 180) return "the vertical angles are not within 0 to 180";
  if (!StrictlyIncreasing(h)) return "the horizontal angles are not strictly increasing";
  const bool symmetric = h.size() == 1 && h.front() == 0;
  const bool from_zero =
      h.size() > 1 && h.front() == 0 && (h.back() == 90 || h.back() == 180 || h.back() == 360);
  const bool from_ninety = h.size() > 1 && h.front() == 90 && h.back() == 270;
  if (!symmetric && !from_zero && !from_ninety) {
    return "the horizontal angles are not 0 alone, 0 to 90, 0 to 180, 90 to 270 or 0 to 360";
  }
  if (table.candela.size() != v.size() * h.size()) {
    return "the table has " + std::to_string(table.candela.size()) + " candela values, not " +
           std::to_string(v.size() * h.size());
  }
  for (double c : table.candela) {
    if (!std::isfinite(c) || c < 0) return "a candela value is negative or not finite";
  }
  return "";
}

double CandelaAt(const CandelaTable& table, double theta_deg, double phi_deg) {
  double phi = std::fmod(phi_deg, 360.0);
  if (phi < 0) phi += 360;
  phi = FoldPhi(table.horizontal, phi);
  size_t h = 0;
  double t = 0;
  if (!Bracket(table.horizontal, phi, &h, &t)) return 0;
  const double a = PlaneAt(table, h, theta_deg);
  if (t == 0) return a;
  return a + (PlaneAt(table, h + 1, theta_deg) - a) * t;
}

double TableLumens(const CandelaTable& table) {
  // Quarter-degree steps in theta; in phi only where the table varies with it.
  constexpr int kThetaSteps = 720;
  const int phi_steps = table.horizontal.size() == 1 ? 1 : 1440;
  const double d_theta = std::numbers::pi / kThetaSteps;
  const double d_phi = 2 * std::numbers::pi / phi_steps;
  double total = 0;
  for (int i = 0; i < kThetaSteps; ++i) {
    const double theta = (i + 0.5) * d_theta;
    double ring = 0;
    for (int j = 0; j < phi_steps; ++j) {
      ring += CandelaAt(table, theta * 180 / std::numbers::pi, (j + 0.5) * 360.0 / phi_steps);
    }
    total += ring * std::sin(theta);
  }
  return total * d_theta * d_phi;
}

}  // namespace radfarm
