// Lightmaps of an OBJ scene, which has no second UV set: the Cornell box rendered by the real
// binary gets charts made for every object. Each object's lit.glb primitive carries them as
// TEXCOORD_1; the lightmap read bilinearly on either side of every seam (a 3D edge whose two
// triangles lie apart in UV) gives the same light where the display is continuous (no visible
// seam), and each side's light is the display's (COLOR_0) at the edge; gutters take a few percent
// of the texels at the default density.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli/exit_codes.h"
#include "output/uv_raster.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"
#include "tests/cli/lightmap_files.h"

namespace radfarm {
namespace {

using testing::RunCommand;
using testing::TempDir;

using Point = std::array<float, 3>;

// One side of a 3D edge: its endpoints' UVs and colours, in the order of the edge's key.
struct Side {
  std::array<std::array<float, 2>, 2> uv;
  std::array<double, 2> colour;  // r + g + b
};

struct SeamStats {
  size_t points = 0;             // seam points sampled, lit above 1% of the brightest
  size_t continuous = 0;         // those where the display is continuous across the seam
  double worst_jump = 0;         // |left - right| / local, where continuous
  std::vector<double> off_side;  // |lightmap - COLOR_0| / COLOR_0 on each side, every point
};

void MeasureSeams(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                  const Exr& exr, SeamStats* stats) {
  const auto positions = ReadAccessor<3>(model, primitive.attributes.at("POSITION"));
  const auto colours = ReadAccessor<3>(model, primitive.attributes.at("COLOR_0"));
  const auto uvs = ReadAccessor<2>(model, primitive.attributes.at("TEXCOORD_1"));
  const auto indices = ReadAccessor<1, uint32_t>(model, primitive.indices);
  double brightest = 0;
  for (const auto& c : colours) brightest = std::max(brightest, double(c[0] + c[1] + c[2]));
  std::map<std::pair<Point, Point>, std::vector<Side>> edges;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = indices[t + k][0], b = indices[t + (k + 1) % 3][0];
      if (positions[b] < positions[a]) std::swap(a, b);
      const auto sum = [&](uint32_t v) {
        return double(colours[v][0] + colours[v][1] + colours[v][2]);
      };
      edges[{positions[a], positions[b]}].push_back({{uvs[a], uvs[b]}, {sum(a), sum(b)}});
    }
  }
  const double texel = 1.0 / exr.width;
  const auto light = [&](double u, double v) {
    return exr.Sample(0, u, v) + exr.Sample(1, u, v) + exr.Sample(2, u, v);
  };
  for (const auto& [edge, sides] : edges) {
    if (sides.size() != 2) continue;
    const Side& l = sides[0];
    const Side& r = sides[1];
    double apart = 0;
    for (int e = 0; e < 2; ++e) {
      apart = std::max({apart, std::abs(l.uv[e][0] - r.uv[e][0]) / texel,
                        std::abs(l.uv[e][1] - r.uv[e][1]) / texel});
    }
    if (apart < 0.5) continue;  // the same place in UV: not a seam
    for (double f = 0.125; f < 1; f += 0.25) {
      const auto lerp = [f](double a, double b) { return (1 - f) * a + f * b; };
      const double cl = lerp(l.colour[0], l.colour[1]), cr = lerp(r.colour[0], r.colour[1]);
      const double local = 0.5 * (cl + cr);
      if (local < 0.01 * brightest) continue;
      const double ll = light(lerp(l.uv[0][0], l.uv[1][0]), lerp(l.uv[0][1], l.uv[1][1]));
      const double lr = light(lerp(r.uv[0][0], r.uv[1][0]), lerp(r.uv[0][1], r.uv[1][1]));
      ++stats->points;
      stats->off_side.push_back(std::abs(ll - cl) / cl);
      stats->off_side.push_back(std::abs(lr - cr) / cr);
      if (std::abs(cl - cr) > 1e-3 * local) continue;
      ++stats->continuous;
      stats->worst_jump = std::max(stats->worst_jump, std::abs(ll - lr) / local);
    }
  }
}

// Texels the stitched border around the charts takes, as the writer draws it, of all texels.
double GutterFraction(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                      const Exr& exr) {
  const auto uvs = ReadAccessor<2>(model, primitive.attributes.at("TEXCOORD_1"));
  const auto indices = ReadAccessor<1, uint32_t>(model, primitive.indices);
  UvRaster raster(uint32_t(exr.width), uint32_t(exr.height));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    std::array<Uv, 3> uv;
    for (int k = 0; k < 3; ++k) uv[k] = uvs[indices[t + k][0]];
    raster.Draw(uv, {Rgb(1, 1, 1), Rgb(1, 1, 1), Rgb(1, 1, 1)});
  }
  raster.Extend(1.0);
  return double(raster.stats().extended) / (double(exr.width) * exr.height);
}

TEST(UnwrappedLightmapTest, TheCornellBoxObjGetsStitchedLightmapsWithThinGutters) {
  TempDir dir;
  const std::string out = dir.path() + "/out";
  const testing::CommandResult r =
      RunCommand({RADFARM_CLI_PATH, "render", RADFARM_SOURCE_DIR "/scenes/cornell-box.toml",
                  "--out", out, "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.err.find("overlap"), std::string::npos) << r.err;

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, out + "/lit.glb")) << err;
  SeamStats seams;
  size_t objects = 0;
  for (const tinygltf::Node& node : model.nodes) {
    if (node.mesh < 0) continue;
    SCOPED_TRACE(node.name);
    ++objects;
    const tinygltf::Primitive& primitive = model.meshes.at(node.mesh).primitives.at(0);
    ASSERT_TRUE(primitive.attributes.count("TEXCOORD_1"));
    const tinygltf::Material& material = model.materials.at(primitive.material);
    const std::string exr_path =
        material.extras.Get("radfarm").Get("lightmap_exr").Get<std::string>();
    EXPECT_EQ(exr_path, "lightmaps/" + node.name + ".exr");
    const Exr exr = ReadExr(out + "/" + exr_path);
    MeasureSeams(model, primitive, exr, &seams);
    const double gutter = GutterFraction(model, primitive, exr);
    std::printf("%s: %d x %d texels, %.2f %% in gutters\n", node.name.c_str(), exr.width,
                exr.height, 100 * gutter);
    EXPECT_LE(gutter, 0.05);
  }
  EXPECT_EQ(objects, 8u);
  std::sort(seams.off_side.begin(), seams.off_side.end());
  ASSERT_GT(seams.points, 0u);
  const double median = seams.off_side[seams.off_side.size() / 2];
  const double p90 = seams.off_side[seams.off_side.size() * 9 / 10];
  std::printf(
      "%zu seam points, %zu where the display is continuous: worst jump %.5f; lightmap against "
      "COLOR_0 on each side: median %.5f, 90th percentile %.5f, worst %.5f\n",
      seams.points, seams.continuous, seams.worst_jump, median, p90, seams.off_side.back());
  EXPECT_GT(seams.continuous, 0u);
  EXPECT_LT(seams.worst_jump, 0.01);
  EXPECT_LT(median, 0.01);
}

}  // namespace
}  // namespace radfarm
