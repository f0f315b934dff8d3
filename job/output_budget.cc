#include "job/output_budget.h"

#include <string>

#include "mesh/memory_estimate.h"

namespace radfarm {

uint64_t EstimatedImageBytes(const Camera& camera) {
  return uint64_t{camera.width} * camera.height * kImageBytesPerPixel;
}

Status CheckPixelSamples(const Camera& camera) {
  const uint64_t samples = uint64_t{camera.width} * camera.height * camera.samples_per_pixel;
  if (samples <= kMaxPixelSamples) return Ok{};
  return Error{"camera: " + std::to_string(camera.width) + " x " + std::to_string(camera.height) +
               " pixels x " + std::to_string(camera.samples_per_pixel) +
               " samples = " + std::to_string(samples) + " pixel samples, more than the limit of " +
               std::to_string(kMaxPixelSamples) +
               "; use fewer samples_per_pixel or a smaller image"};
}

Status CheckOutputBudget(const Camera& camera, uint64_t max_memory) {
  RADFARM_RETURN_IF_ERROR(CheckPixelSamples(camera));
  const uint64_t limit = max_memory > 0 ? max_memory : PhysicalMemoryBytes();
  const uint64_t bytes = EstimatedImageBytes(camera);
  if (limit == 0 || bytes <= limit) return Ok{};
  return Error{"camera: a " + std::to_string(camera.width) + " x " + std::to_string(camera.height) +
               " image needs about " + FormatMegabytes(bytes) +
               " of memory, more than the limit of " + FormatMegabytes(limit) +
               (max_memory > 0 ? " (--max-memory)" : " (this machine's memory)") +
               "; use a smaller image"};
}

uint64_t EstimatedLightmapBytes(uint32_t size) {
  return uint64_t{size} * size * kLightmapBytesPerTexel;
}

Status CheckLightmapBudget(uint32_t size, uint64_t max_memory) {
  const uint64_t limit = max_memory > 0 ? max_memory : PhysicalMemoryBytes();
  const uint64_t bytes = EstimatedLightmapBytes(size);
  if (limit == 0 || bytes <= limit) return Ok{};
  const std::string side = std::to_string(size);
  return Error{"output.lightmap_size: a " + side + " x " + side + " lightmap needs about " +
               FormatMegabytes(bytes) + " of memory, more than the limit of " +
               FormatMegabytes(limit) +
               (max_memory > 0 ? " (--max-memory)" : " (this machine's memory)") +
               "; use a smaller lightmap_size"};
}

}  // namespace radfarm
