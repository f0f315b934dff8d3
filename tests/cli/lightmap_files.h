// Test helpers that read a render's lightmaps and lit.glb back with the libraries' own readers.
#pragma once

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <vector>

namespace radfarm {

struct Exr {
  int width = 0, height = 0;
  std::vector<float> rgb[3];
  // Bilinear at (u, v), glTF's UV: v down from the top row, texel centres at (i + 0.5) / size.
  double Sample(int c, double u, double v) const {
    const double x = std::clamp(u * width - 0.5, 0.0, width - 1.0);
    const double y = std::clamp(v * height - 0.5, 0.0, height - 1.0);
    const int x0 = std::min(int(x), width - 2), y0 = std::min(int(y), height - 2);
    const double fx = x - x0, fy = y - y0;
    const auto at = [&](int xi, int yi) { return double(rgb[c][size_t(yi) * width + xi]); };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
  }
};

inline Exr ReadExr(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  Exr out;
  out.width = window.max.x - window.min.x + 1;
  out.height = window.max.y - window.min.y + 1;
  Imf::FrameBuffer frame;
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    out.rgb[c].resize(size_t(out.width) * out.height);
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(out.rgb[c].data()),
                                      sizeof(float), out.width * sizeof(float)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return out;
}

template <int N, typename T = float>
std::vector<std::array<T, N>> ReadAccessor(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors.at(index);
  const tinygltf::BufferView& v = model.bufferViews.at(a.bufferView);
  std::vector<std::array<T, N>> out(a.count);
  std::memcpy(out.data(), model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset,
              a.count * sizeof(T) * N);
  return out;
}

}  // namespace radfarm
