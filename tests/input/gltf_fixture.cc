#include "tests/input/gltf_fixture.h"

#include <cstring>
#include <fstream>

namespace radfarm::testing {
namespace {

std::string Base64(const std::vector<uint8_t>& bytes) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kAlphabet[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

void Put32(std::vector<uint8_t>* out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out->push_back(static_cast<uint8_t>(v >> (8 * k)));
}

}  // namespace

std::vector<uint8_t> BmpImage(int width, int height, const std::vector<uint8_t>& rgb) {
  const int row = (3 * width + 3) / 4 * 4;
  std::vector<uint8_t> out = {'B', 'M'};
  Put32(&out, 54 + row * height);
  Put32(&out, 0);
  Put32(&out, 54);
  Put32(&out, 40);
  Put32(&out, width);
  Put32(&out, height);
  out.insert(out.end(), {1, 0, 24, 0});
  for (int k = 0; k < 6; ++k) Put32(&out, 0);
  for (int y = height - 1; y >= 0; --y) {  // BMP rows run bottom up
    for (int x = 0; x < width; ++x) {
      const uint8_t* p = &rgb[3 * (y * width + x)];
      out.insert(out.end(), {p[2], p[1], p[0]});
    }
    for (int pad = 3 * width; pad < row; ++pad) out.push_back(0);
  }
  return out;
}

std::vector<uint8_t> PngHeaderOnly(uint32_t width, uint32_t height, int bit_depth,
                                   int colour_type) {
  std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n',
                              0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  for (uint32_t v : {width, height}) {
    for (int k = 3; k >= 0; --k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
  }
  out.insert(out.end(), {static_cast<uint8_t>(bit_depth), static_cast<uint8_t>(colour_type), 0, 0,
                         0, 0, 0, 0, 0});  // compression, filter, interlace, CRC (unchecked)
  return out;
}

GltfFixture::GltfFixture() {
  json_ = {{"asset", {{"version", "2.0"}}},
           {"scene", 0},
           {"scenes", {{{"nodes", nlohmann::json::array()}}}},
           {"nodes", nlohmann::json::array()},
           {"meshes", nlohmann::json::array()},
           {"materials", nlohmann::json::array()},
           {"accessors", nlohmann::json::array()},
           {"bufferViews", nlohmann::json::array()}};
}

int GltfFixture::AddView(const void* data, size_t bytes) {
  const size_t offset = buffer_.size();
  buffer_.resize(offset + bytes);
  std::memcpy(buffer_.data() + offset, data, bytes);
  while (buffer_.size() % 4) buffer_.push_back(0);
  json_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
  return static_cast<int>(json_["bufferViews"].size()) - 1;
}

int GltfFixture::AddPositions(const std::vector<std::array<float, 3>>& points) {
  const int view = AddView(points.data(), points.size() * 12);
  json_["accessors"].push_back(
      {{"bufferView", view}, {"componentType", 5126}, {"count", points.size()}, {"type", "VEC3"}});
  return static_cast<int>(json_["accessors"].size()) - 1;
}

int GltfFixture::AddTexCoords(const std::vector<std::array<float, 2>>& uvs) {
  const int view = AddView(uvs.data(), uvs.size() * 8);
  json_["accessors"].push_back(
      {{"bufferView", view}, {"componentType", 5126}, {"count", uvs.size()}, {"type", "VEC2"}});
  return static_cast<int>(json_["accessors"].size()) - 1;
}

int GltfFixture::AddIndices(const std::vector<uint16_t>& indices) {
  const int view = AddView(indices.data(), indices.size() * 2);
  json_["accessors"].push_back({{"bufferView", view},
                                {"componentType", 5123},
                                {"count", indices.size()},
                                {"type", "SCALAR"}});
  return static_cast<int>(json_["accessors"].size()) - 1;
}

int GltfFixture::AddMesh(const std::string& name, int positions, int indices, int material, int uv,
                         int mode) {
  nlohmann::json primitive = {{"attributes", {{"POSITION", positions}}}, {"mode", mode}};
  if (indices >= 0) primitive["indices"] = indices;
  if (material >= 0) primitive["material"] = material;
  if (uv >= 0) primitive["attributes"]["TEXCOORD_0"] = uv;
  json_["meshes"].push_back({{"name", name}, {"primitives", {primitive}}});
  return static_cast<int>(json_["meshes"].size()) - 1;
}

int GltfFixture::AddMaterial(const nlohmann::json& material) {
  json_["materials"].push_back(material);
  return static_cast<int>(json_["materials"].size()) - 1;
}

int GltfFixture::AddNode(const nlohmann::json& node, bool root) {
  json_["nodes"].push_back(node);
  const int index = static_cast<int>(json_["nodes"].size()) - 1;
  if (root) json_["scenes"][0]["nodes"].push_back(index);
  return index;
}

int GltfFixture::AddTexture(int width, int height, const std::vector<uint8_t>& rgb) {
  json_["images"].push_back(
      {{"uri", "data:image/bmp;base64," + Base64(BmpImage(width, height, rgb))}});
  json_["textures"].push_back({{"source", json_["images"].size() - 1}});
  return static_cast<int>(json_["textures"].size()) - 1;
}

std::string GltfFixture::WriteGltf(const std::string& path) const {
  nlohmann::json doc = json_;
  doc["buffers"] = {{{"byteLength", buffer_.size()},
                     {"uri", "data:application/octet-stream;base64," + Base64(buffer_)}}};
  std::ofstream(path) << doc.dump(1);
  return path;
}

std::string GltfFixture::WriteGlb(const std::string& path) const {
  nlohmann::json doc = json_;
  doc["buffers"] = {{{"byteLength", buffer_.size()}}};
  std::string chunk = doc.dump();
  while (chunk.size() % 4) chunk += ' ';
  std::vector<uint8_t> bin = buffer_;
  std::vector<uint8_t> out = {'g', 'l', 'T', 'F'};
  Put32(&out, 2);
  Put32(&out, static_cast<uint32_t>(12 + 8 + chunk.size() + 8 + bin.size()));
  Put32(&out, static_cast<uint32_t>(chunk.size()));
  out.insert(out.end(), {'J', 'S', 'O', 'N'});
  out.insert(out.end(), chunk.begin(), chunk.end());
  Put32(&out, static_cast<uint32_t>(bin.size()));
  out.insert(out.end(), {'B', 'I', 'N', 0});
  out.insert(out.end(), bin.begin(), bin.end());
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
  return path;
}

GltfFixture FloorAndLight() {
  GltfFixture f;
  const int grey = f.AddMaterial(
      {{"name", "floor"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  const int lamp = f.AddMaterial(
      {{"name", "lamp"},
       {"emissiveFactor", {1, 0.5, 0.25}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}});
  f.json()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  const int floor_points = f.AddPositions({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}});
  const int floor_indices = f.AddIndices({0, 1, 2, 0, 2, 3});
  f.AddNode({{"name", "Floor"}, {"mesh", f.AddMesh("floor", floor_points, floor_indices, grey)}});
  // Non-indexed, facing down (-y).
  const int lamp_points = f.AddPositions({{0.4f, 0.9f, 0.4f},
                                          {0.6f, 0.9f, 0.4f},
                                          {0.6f, 0.9f, 0.6f},
                                          {0.4f, 0.9f, 0.4f},
                                          {0.6f, 0.9f, 0.6f},
                                          {0.4f, 0.9f, 0.6f}});
  f.AddNode({{"name", "Lamp"}, {"mesh", f.AddMesh("lamp", lamp_points, -1, lamp)}});
  return f;
}

}  // namespace radfarm::testing
