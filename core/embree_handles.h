// An Embree device and scene, owned together and released in reverse order of creation, and the
// check of the device's error state. Shared by the solver's RayCaster and the reference bench's
// casters (reference/), each of which keeps one behind its own pimpl.
#pragma once

#include <embree3/rtcore.h>

#include <stdexcept>
#include <string>

namespace radfarm {

struct EmbreeHandles {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  EmbreeHandles() = default;
  EmbreeHandles(const EmbreeHandles&) = delete;
  EmbreeHandles& operator=(const EmbreeHandles&) = delete;
  ~EmbreeHandles() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

// Throws std::runtime_error("Embree error N in WHAT") when `device` reports an error.
inline void ThrowOnEmbreeError(RTCDevice device, const std::string& what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    throw std::runtime_error("Embree error " + std::to_string(int(error)) + " in " + what);
  }
}

}  // namespace radfarm
