#include "output/exposure_meter.h"

#include <algorithm>

#include "output/image.h"
#include "output/tone_map.h"

namespace radfarm {
namespace {

// A small view is enough to meter: the percentile is over area, not detail.
constexpr uint32_t kMeterSize = 128;

}  // namespace

Camera MeterExposure(const DisplayMesh& mesh, const std::vector<bool>& emitter_patch,
                     const Camera& camera) {
  if (!camera.auto_exposure) return camera;
  DisplayMesh lit;
  lit.positions = mesh.positions;
  lit.radiance = mesh.radiance;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const uint32_t patch = mesh.triangle_patch[t];
    // Emitters still occlude, but as black: they must not count, and must not reveal what is
    // behind them either.
    if (patch < emitter_patch.size() && emitter_patch[patch]) {
      for (uint32_t v : mesh.triangles[t]) {
        lit.radiance.push_back(Rgb{});
        lit.positions.push_back(mesh.positions[v]);
      }
      const auto n = static_cast<uint32_t>(lit.positions.size());
      lit.triangles.push_back({n - 3, n - 2, n - 1});
    } else {
      lit.triangles.push_back(mesh.triangles[t]);
    }
    lit.triangle_patch.push_back(patch);
  }
  Camera meter = camera;
  const double aspect = double(camera.width) / std::max(1u, camera.height);
  meter.width = aspect >= 1 ? kMeterSize : std::max(1u, uint32_t(kMeterSize * aspect));
  meter.height = aspect >= 1 ? std::max(1u, uint32_t(kMeterSize / aspect)) : kMeterSize;
  meter.samples_per_pixel = 1;
  Camera resolved = camera;
  resolved.exposure = AutoExposureStops(RenderImage(lit, meter)) + camera.exposure;
  resolved.auto_exposure = false;
  return resolved;
}

}  // namespace radfarm
