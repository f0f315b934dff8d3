// Small glTF files written by the tests themselves: a JSON document (nlohmann) and one binary
// buffer, saved as .gltf (buffer as a data URI) or .glb.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace radfarm::testing {

class GltfFixture {
 public:
  GltfFixture();

  // Appends data to the buffer and returns a new accessor's index.
  int AddPositions(const std::vector<std::array<float, 3>>& points);
  int AddTexCoords(const std::vector<std::array<float, 2>>& uvs);
  int AddIndices(const std::vector<uint16_t>& indices);
  // A mesh of one primitive; `indices` -1 for none, `uv` -1 for no TEXCOORD_0. Returns its index.
  int AddMesh(const std::string& name, int positions, int indices, int material, int uv = -1,
              int mode = 4);
  int AddMaterial(const nlohmann::json& material);
  // A node, listed among the scene's roots when `root`. Returns its index.
  int AddNode(const nlohmann::json& node, bool root = true);
  // A 24-bit BMP image of width x height (RGB bytes, top row first) as the texture's source.
  int AddTexture(int width, int height, const std::vector<uint8_t>& rgb);

  nlohmann::json& json() { return json_; }
  std::string WriteGltf(const std::string& path) const;
  std::string WriteGlb(const std::string& path) const;

 private:
  int AddView(const void* data, size_t bytes);
  nlohmann::json json_;
  std::vector<uint8_t> buffer_;
};

// A 24-bit BMP file of width x height pixels (RGB bytes, top row first).
std::vector<uint8_t> BmpImage(int width, int height, const std::vector<uint8_t>& rgb);

// A PNG of its header alone (signature and IHDR chunk), declaring width x height pixels of
// `bit_depth` bits and PNG colour type `colour_type` (6: RGBA): a few bytes that claim any size.
std::vector<uint8_t> PngHeaderOnly(uint32_t width, uint32_t height, int bit_depth, int colour_type);

// A floor quad (y = 0, 1 m square, facing +y) and a small emissive quad above it facing down, as
// two meshes under their own nodes: the smallest scene that loads.
GltfFixture FloorAndLight();

}  // namespace radfarm::testing
