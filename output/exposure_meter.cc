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
  // Emitters still occlude, but as black: they must not count, and must not reveal what is behind
  // them either.
  Camera meter = camera;
  const double aspect = double(camera.width) / std::max(1u, camera.height);
  meter.width = aspect >= 1 ? kMeterSize : std::max(1u, uint32_t(kMeterSize * aspect));
  meter.height = aspect >= 1 ? std::max(1u, uint32_t(kMeterSize / aspect)) : kMeterSize;
  meter.samples_per_pixel = 1;
  Camera resolved = camera;
  resolved.exposure = AutoExposureStops(RenderImage(mesh, meter, emitter_patch)) + camera.exposure;
  resolved.auto_exposure = false;
  return resolved;
}

}  // namespace radfarm
