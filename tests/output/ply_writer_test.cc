#include "output/ply_writer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <sstream>
#include <vector>

#include "output/tone_map.h"
#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

DisplayMesh Square() {
  DisplayMesh mesh;
  mesh.positions = {{0, 0, 5}, {1, 0, 5}, {1, 1, 5}, {0, 1, 5}};
  mesh.radiance = {{0.5, 0.25, 0}, {1, 1, 1}, {0.125, 0, 2}, {0.1, 0.2, 0.3}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.triangle_patch = {0, 0};
  return mesh;
}

struct ParsedPly {
  std::vector<std::string> header_lines;
  std::string body;
};

ParsedPly Parse(const std::string& bytes) {
  ParsedPly parsed;
  const std::string end = "end_header\n";
  const size_t header_end = bytes.find(end);
  if (header_end == std::string::npos) return parsed;
  std::istringstream header(bytes.substr(0, header_end + end.size()));
  for (std::string line; std::getline(header, line);) parsed.header_lines.push_back(line);
  parsed.body = bytes.substr(header_end + end.size());
  return parsed;
}

template <typename T>
T Read(const std::string& body, size_t* offset) {
  T value;
  std::memcpy(&value, body.data() + *offset, sizeof(T));  // the test host is little-endian
  *offset += sizeof(T);
  return value;
}

TEST(PlyWriterTest, HeaderAndBodyParseBack) {
  TestDir dir;
  const std::string path = dir.File("mesh.ply");
  Camera camera;
  camera.auto_exposure = false;
  camera.exposure = 1;
  const DisplayMesh mesh = Square();
  ASSERT_TRUE(WritePly(path, mesh, camera).ok());

  const ParsedPly ply = Parse(ReadFileBytes(path));
  std::vector<std::string> expected_header = {
      "ply",
      "format binary_little_endian 1.0",
      "element vertex 4",
      "property float x",
      "property float y",
      "property float z",
      "property uchar red",
      "property uchar green",
      "property uchar blue",
      "property float radiance_r",
      "property float radiance_g",
      "property float radiance_b",
      "element face 2",
      "property list uchar int vertex_indices",
      "end_header",
  };
  std::vector<std::string> header_without_comments;
  for (const std::string& line : ply.header_lines) {
    if (line.rfind("comment ", 0) != 0) header_without_comments.push_back(line);
  }
  EXPECT_EQ(header_without_comments, expected_header);
  ASSERT_EQ(ply.body.size(), 4u * (3 * 4 + 3 + 3 * 4) + 2u * (1 + 3 * 4));

  size_t offset = 0;
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(Read<float>(ply.body, &offset), static_cast<float>(mesh.positions[i].x));
    EXPECT_EQ(Read<float>(ply.body, &offset), static_cast<float>(mesh.positions[i].y));
    EXPECT_EQ(Read<float>(ply.body, &offset), static_cast<float>(mesh.positions[i].z));
    const std::array<uint8_t, 3> colour = ToneMapPixel(mesh.radiance[i], 2.0);  // +1 stop
    EXPECT_EQ(Read<uint8_t>(ply.body, &offset), colour[0]);
    EXPECT_EQ(Read<uint8_t>(ply.body, &offset), colour[1]);
    EXPECT_EQ(Read<uint8_t>(ply.body, &offset), colour[2]);
    EXPECT_EQ(Read<float>(ply.body, &offset), static_cast<float>(mesh.radiance[i].r));
    EXPECT_EQ(Read<float>(ply.body, &offset), static_cast<float>(mesh.radiance[i].g));
    EXPECT_EQ(Read<float>(ply.body, &offset), static_cast<float>(mesh.radiance[i].b));
  }
  for (const auto& triangle : mesh.triangles) {
    EXPECT_EQ(Read<uint8_t>(ply.body, &offset), 3);
    for (uint32_t index : triangle) EXPECT_EQ(Read<int32_t>(ply.body, &offset), int32_t(index));
  }
  // Vertex 0 at +1 stop: (1, 0.5, 0) -> (255, 188, 0).
  EXPECT_EQ(ToneMapPixel(mesh.radiance[0], 2.0), (std::array<uint8_t, 3>{255, 188, 0}));
}

TEST(PlyWriterTest, AutoExposureMatchesTheImage) {
  TestDir dir;
  const std::string path = dir.File("auto.ply");
  DisplayMesh mesh = Square();
  for (Rgb& r : mesh.radiance) r = {0.02, 0.02, 0.02};
  ASSERT_TRUE(WritePly(path, mesh, Camera{}).ok());  // automatic camera, auto exposure
  const ParsedPly ply = Parse(ReadFileBytes(path));
  // A uniformly lit mesh meters to white.
  EXPECT_EQ(static_cast<uint8_t>(ply.body[12]), 255);
  EXPECT_EQ(static_cast<uint8_t>(ply.body[13]), 255);
  EXPECT_EQ(static_cast<uint8_t>(ply.body[14]), 255);
}

TEST(PlyWriterTest, RejectsInconsistentMeshes) {
  TestDir dir;
  const std::string path = dir.File("bad.ply");
  DisplayMesh mesh = Square();
  mesh.radiance.pop_back();
  Status status = WritePly(path, mesh, Camera{});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(path), std::string::npos) << status.error();

  mesh = Square();
  mesh.triangles.push_back({0, 1, 4});
  status = WritePly(path, mesh, Camera{});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find("vertex 4"), std::string::npos) << status.error();
  EXPECT_TRUE(dir.Entries().empty());
}

TEST(PlyWriterTest, MissingDirectoryNamesThePath) {
  TestDir dir;
  const std::string path = dir.File("absent/mesh.ply");
  const Status status = WritePly(path, Square(), Camera{});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(path), std::string::npos) << status.error();
}

}  // namespace
}  // namespace radfarm
