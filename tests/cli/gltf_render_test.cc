// glTF scenes and two-sided surfaces end to end: the Cornell box as glTF and GLB (scenes/, written
// by scenes/make-cornell-box-gltf.py) renders like the OBJ; a room whose walls face outward is
// lit inside when two-sided, and warns when not. Runs the real binary.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/outward_cube.h"
#include "testing/png_size.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

using testing::OutwardCube;
using testing::PngSize;
using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

const std::string kSceneDir = RADFARM_SOURCE_DIR "/scenes/";

testing::CommandResult RenderScene(const std::string& scene, const std::string& out,
                                   std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {RADFARM_CLI_PATH, "render", scene, "--out", out, "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  return RunCommand(args);
}

std::string WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

struct CsvPatch {
  std::string material;
  double area = 0;
  double c[3] = {}, n[3] = {}, rgb[3] = {};
};

std::vector<CsvPatch> ReadCsvPatches(const std::string& path) {
  std::vector<CsvPatch> patches;
  std::istringstream in(ReadFile(path));
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream cell_stream(line);
    for (std::string cell; std::getline(cell_stream, cell, ',');) cells.push_back(cell);
    if (cells.size() != 13) continue;
    CsvPatch p;
    p.material = cells[2];
    p.area = std::stod(cells[3]);
    for (int k = 0; k < 3; ++k) {
      p.c[k] = std::stod(cells[4 + k]);
      p.n[k] = std::stod(cells[7 + k]);
      p.rgb[k] = std::stod(cells[10 + k]);
    }
    patches.push_back(p);
  }
  return patches;
}

// Area-weighted mean of r + g + b per material.
std::map<std::string, double> MaterialMeans(const std::vector<CsvPatch>& patches) {
  std::map<std::string, std::pair<double, double>> sums;
  for (const CsvPatch& p : patches) {
    sums[p.material].first += p.area * (p.rgb[0] + p.rgb[1] + p.rgb[2]);
    sums[p.material].second += p.area;
  }
  std::map<std::string, double> means;
  for (const auto& [name, s] : sums) means[name] = s.first / s.second;
  return means;
}

TEST(GltfRenderTest, CornellBoxAsGltfAndGlbRendersLikeTheObj) {
  TempDir dir;
  // The same coarse settings for all three; millimetres for the OBJ, metres for glTF.
  const std::string settings = "[solver]\ntolerance = 0.01\ngather_rays = 256\n";
  const std::string obj_job =
      WriteText(dir.File("obj.toml"), "scene = \"" + kSceneDir + "cornell-box.obj\"\n" + settings +
                                          "[mesh]\npatch_size = 50.0\n");
  const std::string gltf_job =
      WriteText(dir.File("gltf.toml"), "scene = \"" + kSceneDir + "cornell-box.gltf\"\n" +
                                           settings + "[mesh]\npatch_size = 0.05\n");
  const std::string glb_job =
      WriteText(dir.File("glb.toml"), "scene = \"" + kSceneDir + "cornell-box.glb\"\n" + settings +
                                          "[mesh]\npatch_size = 0.05\n");
  std::map<std::string, std::map<std::string, double>> means;
  std::map<std::string, std::string> csv;
  for (const std::string& job : {obj_job, gltf_job, glb_job}) {
    SCOPED_TRACE(job);
    TempDir out;
    const auto r = RenderScene(job, out.path());
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    EXPECT_EQ(r.err.find("lit from behind"), std::string::npos) << r.err;
    means[job] = MaterialMeans(ReadCsvPatches(out.File("patches.csv")));
    csv[job] = ReadFile(out.File("patches.csv"));
  }
  // One file in two encodings: the same bytes out.
  EXPECT_TRUE(csv[gltf_job] == csv[glb_job]);
  // Quads there, triangle pairs here: different patches, the same light within a few percent.
  for (const char* material : {"white", "red", "green", "light"}) {
    const double obj = means[obj_job][material];
    const double gltf = means[gltf_job][material];
    EXPECT_GT(obj, 0) << material;
    EXPECT_NEAR(gltf / obj, 1, 0.03) << material << ": obj " << obj << ", gltf " << gltf;
  }
}

// The lamp-lit box (scenes/cornell-box-lamp.gltf): no emissive triangle, three KHR_lights_punctual
// lamps. It renders, every surface is lit (the blocks' tops by the bulb, the walls by bounces),
// and the panel the bulb hangs under is lit from below; one thread or three, the same bytes.
TEST(GltfRenderTest, ACornellBoxLitByPunctualLampsAloneRendersTheSameOnAnyThreads) {
  TempDir dir;
  const std::string job = WriteText(
      dir.File("lamp.toml"), "scene = \"" + kSceneDir +
                                 "cornell-box-lamp.gltf\"\n[mesh]\npatch_size = 0.05\n"
                                 "[solver]\ntolerance = 0.01\n[camera]\nwidth = 64\nheight = 64\n");
  std::map<std::string, std::string> csv;
  for (const char* threads : {"1", "3"}) {
    TempDir out;
    const auto r = RenderScene(job, out.path(), {"--threads", threads});
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    EXPECT_EQ(r.err.find("nothing to light"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("KHR_lights_punctual"), std::string::npos) << r.err;
    csv[threads] = ReadFile(out.File("patches.csv"));
    const std::map<std::string, double> means =
        MaterialMeans(ReadCsvPatches(out.File("patches.csv")));
    for (const char* material : {"white", "red", "green", "light"}) {
      EXPECT_GT(means.at(material), 0) << material;
    }
  }
  EXPECT_TRUE(csv["1"] == csv["3"]) << "thread counts differ";
}

// A 16:9 glTF camera renders a 16:9 image: the width follows the height (512 unless the job
// gives it), or the height the width; a job that gives both keeps them.
TEST(GltfRenderTest, TheCamerasAspectRatioShapesTheImage) {
  TempDir dir;
  std::string gltf = ReadFile(kSceneDir + "cornell-box.gltf");
  const size_t at = gltf.find("\"aspectRatio\"");
  ASSERT_NE(at, std::string::npos);
  const size_t end = gltf.find_first_of(",}", at);
  gltf.replace(at, end - at, "\"aspectRatio\": 1.7777778");
  WriteText(dir.File("wide.gltf"), gltf);
  const std::string settings = "[mesh]\npatch_size = 0.2\n[solver]\ntolerance = 0.2\n";
  const std::vector<std::pair<std::string, std::pair<uint32_t, uint32_t>>> cases = {
      {"", {910, 512}},
      {"[camera]\nheight = 90\n", {160, 90}},
      {"[camera]\nwidth = 64\n", {64, 36}},
      {"[camera]\nwidth = 64\nheight = 64\n", {64, 64}}};
  for (const auto& [camera, size] : cases) {
    SCOPED_TRACE(camera);
    const std::string job =
        WriteText(dir.File("wide.toml"), "scene = \"wide.gltf\"\n" + settings + camera);
    TempDir out;
    const auto r = RenderScene(job, out.path());
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    EXPECT_EQ(PngSize(out.File("image.png")), size);
  }
}

TEST(GltfRenderTest, AnUnknownCameraNameIsBadInput) {
  TempDir out;
  const auto r = RenderScene(kSceneDir + "cornell-box.glb", out.path(), {"--camera", "nope"});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_NE(r.err.find("cornell-box.glb: no camera named 'nope' (cameras: 'Camera')"),
            std::string::npos)
      << r.err;
}

TEST(GltfRenderTest, AnOutwardFacingRoomWarnsAndIsLitWhenTwoSided) {
  TempDir dir;
  WriteText(dir.File("room.mtl"),
            "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
  WriteText(dir.File("room.obj"), OutwardCube("wall", true));
  const std::string settings = "[mesh]\npatch_size = 0.1\n[solver]\ngather_rays = 64\n";
  const std::string one_sided =
      WriteText(dir.File("one.toml"), "scene = \"room.obj\"\n" + settings);
  const std::string two_sided =
      WriteText(dir.File("two.toml"),
                "scene = \"room.obj\"\n" + settings + "[materials.wall]\ntwo_sided = true\n");
  {
    TempDir out;
    const auto r = RenderScene(one_sided, out.path());
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    EXPECT_NE(r.err.find("room.obj: warning: material 'wall' is lit from behind: 100% of the "
                         "emitters' light"),
              std::string::npos)
        << r.err;
    // The advice names this material's setting: a top-level two_sided would turn lamps too.
    EXPECT_NE(r.err.find("set [materials.wall] two_sided = true in the job file"),
              std::string::npos)
        << r.err;
    EXPECT_DOUBLE_EQ(MaterialMeans(ReadCsvPatches(out.File("patches.csv")))["wall"], 0);
  }
  TempDir out;
  const auto r = RenderScene(two_sided, out.path());
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.err.find("lit from behind"), std::string::npos) << r.err;
  double inside = 0, outside = 0;
  for (const CsvPatch& p : ReadCsvPatches(out.File("patches.csv"))) {
    if (p.material != "wall") continue;
    double outward = 0;
    for (int k = 0; k < 3; ++k) outward += p.n[k] * (p.c[k] - 0.5);
    (outward < 0 ? inside : outside) += p.area * p.rgb[0];
  }
  EXPECT_GT(inside, 0);
  EXPECT_EQ(outside, 0);  // nothing outside lights the walls' outer sides
}

// A closed furnace of two-sided walls that all emit 1 and reflect 0.5: inside, every side sees
// only the inside, so its radiance is E / (1 - rho) = 2; outside it is E = 1 (one patch for both
// sides would read something in between on both).
TEST(GltfRenderTest, ATwoSidedFurnaceReachesEOverOneMinusRhoInsideAndEOutside) {
  TempDir dir;
  WriteText(dir.File("room.mtl"), "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  WriteText(dir.File("room.obj"), OutwardCube("glow", false));
  const std::string job = WriteText(dir.File("furnace.toml"),
                                    "scene = \"room.obj\"\ntwo_sided = true\n[mesh]\n"
                                    "patch_size = 0.25\n[solver]\ntolerance = 0.0001\n"
                                    "gather_rays = 4096\n");
  TempDir out;
  const auto r = RenderScene(job, out.path());
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::vector<CsvPatch> patches = ReadCsvPatches(out.File("patches.csv"));
  ASSERT_EQ(patches.size(), 2u * 6 * 16);
  for (const CsvPatch& p : patches) {
    double outward = 0;
    for (int k = 0; k < 3; ++k) outward += p.n[k] * (p.c[k] - 0.5);
    EXPECT_NEAR(p.rgb[1], outward < 0 ? 2.0 : 1.0, 0.03)
        << "patch at " << p.c[0] << " " << p.c[1] << " " << p.c[2];
  }
}

}  // namespace
}  // namespace radfarm
