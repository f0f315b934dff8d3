#include "job/job_lamp.h"

#include <cmath>
#include <numbers>

namespace radfarm {

Vec3 LampReference(const JobLamp& lamp) {
  const Vec3& a = lamp.aim;
  // Off the aim by more than 25 degrees, so the projection keeps its precision.
  const Vec3 seed = std::abs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, -1};
  const Vec3 zero = Normalize(seed - a * Dot(seed, a));
  const double r = lamp.rotate * std::numbers::pi / 180;
  return Normalize(zero * std::cos(r) + Cross(zero, a) * std::sin(r));
}

}  // namespace radfarm
