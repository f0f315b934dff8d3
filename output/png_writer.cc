#include "output/png_writer.h"

#include <png.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "base/atomic_file.h"
#include "output/tone_map.h"

namespace radfarm {

Result<std::string> EncodeRgb8Png(uint32_t width, uint32_t height,
                                  const std::vector<uint8_t>& rgb) {
  if (width == 0 || height == 0 || rgb.size() != static_cast<size_t>(width) * height * 3) {
    return Error{"cannot write PNG: image is empty or its size does not match its pixels"};
  }
  if (width > std::numeric_limits<png_int_32>::max() / 3) {
    return Error{"cannot write PNG: image too wide"};
  }
  // libpng's simplified API reports errors through image.message instead of longjmp, and writing
  // to memory lets the atomic-file helper own the file handling.
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = PNG_FORMAT_RGB;  // 8-bit non-linear: libpng tags it as sRGB
  // Speed over size: a render writes a PNG per object beside the image, on the client.
  image.flags = PNG_IMAGE_FLAG_FAST;
  const png_int_32 stride = static_cast<png_int_32>(width * 3);

  // Room for the worst case, so the image is compressed once: asking libpng for the exact size
  // first (png_image_write_get_memory_size) compresses it twice.
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(image);
  std::string encoded(size, '\0');
  if (!png_image_write_to_memory(&image, encoded.data(), &size, 0, rgb.data(), stride, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    return Error{"cannot encode PNG: " + message};
  }
  png_image_free(&image);
  encoded.resize(size);
  return encoded;
}

Result<std::string> EncodePng(const Image& linear, const Camera& camera) {
  if (linear.width == 0 || linear.height == 0 ||
      linear.pixels.size() != static_cast<size_t>(linear.width) * linear.height) {
    return Error{"cannot write PNG: image is empty or its size does not match its pixels"};
  }
  if (linear.width > std::numeric_limits<png_int_32>::max() / 3) {
    return Error{"cannot write PNG: image too wide"};
  }
  return EncodeRgb8Png(linear.width, linear.height, ToneMapImage(linear, camera));
}

Status WritePng(const std::string& path, const Image& linear, const Camera& camera) {
  Result<std::string> encoded = EncodePng(linear, camera);
  if (!encoded) return Error{path + ": " + encoded.error()};
  return WriteFileAtomically(path, *encoded);
}

}  // namespace radfarm
