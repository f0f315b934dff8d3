#include "output/patches_csv.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

PatchScene TwoPatches() {
  PatchScene scene;
  scene.material_names = {"white", "light, warm \"2700K\""};
  Patch a;
  a.area = 0.1;
  a.centre = {1.0 / 3, -2.0 / 7, 1e-300};
  a.normal = {0, 0, -1};
  a.surface = 4;
  a.material = 0;
  Patch b;
  b.area = 123456.789;
  b.centre = {5e-324, std::numeric_limits<double>::max(), -0.0};
  b.normal = {0.6, 0.8, 0};
  b.surface = 7;
  b.material = 1;
  scene.patches = {a, b};
  return scene;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Fields split at commas; the quoted material field is returned unparsed.
std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) {
      fields.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  fields.push_back(field);
  return fields;
}

double ParseDouble(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

TEST(PatchesCsvTest, HeaderAndExactRoundTrip) {
  TestDir dir;
  const std::string path = dir.File("patches.csv");
  const PatchScene scene = TwoPatches();
  const std::vector<Rgb> radiance = {{0.1, 0.2, 0.3}, {1.0 / 3, 2.0 / 3, 1e-17}};
  ASSERT_TRUE(WritePatchesCsv(path, scene, radiance).ok());

  const std::string text = ReadFileBytes(path);
  const std::vector<std::string> lines = Lines(text);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "patch,surface,material,area,cx,cy,cz,nx,ny,nz,r,g,b");
  EXPECT_EQ(text.back(), '\n');
  for (size_t i = 0; i < 2; ++i) {
    const std::vector<std::string> f = Split(lines[i + 1]);
    ASSERT_EQ(f.size(), 13u) << lines[i + 1];
    const Patch& p = scene.patches[i];
    EXPECT_EQ(f[0], std::to_string(i));
    EXPECT_EQ(f[1], std::to_string(p.surface));
    const double expected[] = {p.area,     p.centre.x, p.centre.y,    p.centre.z,    p.normal.x,
                               p.normal.y, p.normal.z, radiance[i].r, radiance[i].g, radiance[i].b};
    for (int k = 0; k < 10; ++k) {
      const double value = ParseDouble(f[3 + k]);
      EXPECT_EQ(value, expected[k]) << "row " << i << " column " << 3 + k << ": " << f[3 + k];
      EXPECT_EQ(std::signbit(value), std::signbit(expected[k]));
    }
  }
  EXPECT_EQ(Split(lines[1])[2], "white");
  EXPECT_EQ(Split(lines[2])[2], "\"light, warm \"\"2700K\"\"\"");
  EXPECT_EQ(Split(lines[1])[3], "0.1");  // shortest form, not 0.10000000000000001
}

TEST(PatchesCsvTest, RewritingGivesIdenticalBytes) {
  TestDir dir;
  const PatchScene scene = TwoPatches();
  const std::vector<Rgb> radiance = {{0.1, 0.2, 0.3}, {1.0 / 3, 2.0 / 3, 1e-17}};
  ASSERT_TRUE(WritePatchesCsv(dir.File("a.csv"), scene, radiance).ok());
  ASSERT_TRUE(WritePatchesCsv(dir.File("b.csv"), scene, radiance).ok());
  EXPECT_EQ(ReadFileBytes(dir.File("a.csv")), ReadFileBytes(dir.File("b.csv")));
}

TEST(PatchesCsvTest, RejectsMismatchedInput) {
  TestDir dir;
  const std::string path = dir.File("patches.csv");
  PatchScene scene = TwoPatches();
  Status status = WritePatchesCsv(path, scene, {{1, 1, 1}});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(path), std::string::npos) << status.error();

  scene.patches[1].material = 9;
  status = WritePatchesCsv(path, scene, {{1, 1, 1}, {1, 1, 1}});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find("patch 1"), std::string::npos) << status.error();
  EXPECT_TRUE(dir.Entries().empty());

  const std::string missing = dir.File("nowhere/patches.csv");
  status = WritePatchesCsv(missing, TwoPatches(), {{1, 1, 1}, {1, 1, 1}});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(missing), std::string::npos) << status.error();
}

}  // namespace
}  // namespace radfarm
