#include "core/warm_start.h"

namespace radfarm {
namespace {

// One channel of H = (B - E) / rho - D; false where it was not recorded (rho was 0) but is
// needed (rho' is not).
bool IncomingBounced(double b, double e, double rho, double d, double rho_now, double* h) {
  if (rho_now == 0) {
    *h = 0;  // reflects nothing now: what it receives does not matter
    return true;
  }
  if (rho == 0) return false;
  *h = (b - e) / rho - d;
  return true;
}

// What a patch sends that shooting spreads: its radiosity less the emission the direct start
// already delivered.
Rgb Sent(const Rgb& radiosity, const Rgb& emission, bool emitters_direct) {
  return emitters_direct ? radiosity - emission : radiosity;
}

}  // namespace

std::optional<WarmState> WarmStartOf(const PatchScene& scene, const std::vector<Rgb>& direct,
                                     bool emitters_direct, const PreviousPatchValues& previous,
                                     uint32_t* black_patch) {
  const size_t n = scene.patches.size();
  WarmState out{std::vector<Rgb>(n), std::vector<Rgb>(n)};
  for (uint32_t i = 0; i < n; ++i) {
    const Patch& p = scene.patches[i];
    const Rgb b = previous.radiosity[i], e = previous.emission[i], rho = previous.reflectance[i];
    const Rgb d = previous.direct.empty() ? Rgb{} : previous.direct[i];
    const Rgb d_now = direct.empty() ? Rgb{} : direct[i];
    Rgb h;
    if (!IncomingBounced(b.r, e.r, rho.r, d.r, p.reflectance.r, &h.r) ||
        !IncomingBounced(b.g, e.g, rho.g, d.g, p.reflectance.g, &h.g) ||
        !IncomingBounced(b.b, e.b, rho.b, d.b, p.reflectance.b, &h.b)) {
      *black_patch = i;
      return std::nullopt;
    }
    out.radiosity[i] = p.emission + p.reflectance * (d_now + h);
    out.unshot[i] = Sent(out.radiosity[i], p.emission, emitters_direct) -
                    Sent(b, e, previous.emitters_direct) + previous.unshot[i];
  }
  return out;
}

}  // namespace radfarm
