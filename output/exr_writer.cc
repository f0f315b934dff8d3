#include "output/exr_writer.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>

#include <exception>
#include <limits>
#include <vector>

#include "base/atomic_file.h"

namespace radfarm {
namespace {

// Encodes into memory; OpenEXR throws on failure, which the caller catches.
std::string EncodeExr(const Image& linear) {
  const int width = static_cast<int>(linear.width);
  const int height = static_cast<int>(linear.height);
  std::vector<float> rgb(linear.pixels.size() * 3);
  for (size_t i = 0; i < linear.pixels.size(); ++i) {
    rgb[3 * i + 0] = static_cast<float>(linear.pixels[i].r);
    rgb[3 * i + 1] = static_cast<float>(linear.pixels[i].g);
    rgb[3 * i + 2] = static_cast<float>(linear.pixels[i].b);
  }

  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  const char* names[] = {"R", "G", "B"};
  for (const char* name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));

  Imf::FrameBuffer frame;
  const size_t x_stride = 3 * sizeof(float);
  const size_t y_stride = x_stride * linear.width;
  for (int c = 0; c < 3; ++c) {
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c), x_stride,
                                      y_stride));
  }

  Imf::StdOSStream stream;
  {
    // The file's offset table is written when OutputFile is destroyed: finish it before str().
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  }
  return stream.str();
}

}  // namespace

Status WriteExr(const std::string& path, const Image& linear) {
  if (linear.width == 0 || linear.height == 0 ||
      linear.pixels.size() != static_cast<size_t>(linear.width) * linear.height) {
    return Error{path + ": cannot write EXR: image is empty or its size does not match its pixels"};
  }
  if (linear.width > static_cast<uint32_t>(std::numeric_limits<int>::max()) ||
      linear.height > static_cast<uint32_t>(std::numeric_limits<int>::max())) {
    return Error{path + ": cannot write EXR: image too large"};
  }
  std::string encoded;
  try {
    encoded = EncodeExr(linear);
  } catch (const std::exception& e) {
    return Error{path + ": cannot encode EXR: " + e.what()};
  } catch (...) {
    return Error{path + ": cannot encode EXR: unknown error"};
  }
  return WriteFileAtomically(path, encoded);
}

}  // namespace radfarm
