// output/illuminance_report.h, output/illuminance_files.h and output/illuminance_planes.h: the
// figures, the CSV and JSON, the files in a directory, and surfaces picked by name.
#include "output/illuminance_report.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "output/illuminance_files.h"
#include "output/illuminance_planes.h"
#include "tests/core/test_scenes.h"
#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

TEST(IlluminanceReportTest, SummaryHoldsMinMeanMaxAndBothUniformities) {
  const LuxSummary s = SummariseLux({300, 100, 200});
  EXPECT_EQ(s.points, 3u);
  EXPECT_EQ(s.min, 100);
  EXPECT_EQ(s.mean, 200);
  EXPECT_EQ(s.max, 300);
  EXPECT_EQ(s.uniformity, 0.5);
  EXPECT_EQ(s.diversity, 100.0 / 300);
  const LuxSummary none = SummariseLux({});
  EXPECT_EQ(none.points, 0u);
  EXPECT_EQ(none.uniformity, 0);
  EXPECT_EQ(SummariseLux({0, 0}).uniformity, 0);  // no light: no uniformity, not a division by 0
}

// Two points on one level and one on another.
PlaneIlluminance TwoLevels() {
  PlaneIlluminance p;
  p.plane = {"desks", 0.8, 0.5, {}};
  p.grid.spacing = 0.5;
  p.grid.columns = 2;
  p.grid.rows = 1;
  p.grid.levels = {0, 3};
  p.grid.cells = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  p.grid.points = {{{0.25, 0.8, 0.25}, {0, 1, 0}},
                   {{0.75, 0.8, 0.25}, {0, 1, 0}},
                   {{0.25, 3.8, 0.25}, {0, 1, 0}}};
  p.lux = {100, 300, 50};
  return p;
}

TEST(IlluminanceReportTest, CsvHasAPointPerLine) {
  EXPECT_EQ(IlluminanceCsv(TwoLevels()),
            "x,y,z,lux\n0.25,0.8,0.25,100\n0.75,0.8,0.25,300\n0.25,3.8,0.25,50\n");
}

TEST(IlluminanceReportTest, JsonHasEveryPlaneAndLevel) {
  EXPECT_EQ(IlluminanceJson({TwoLevels()}),
            "{\n  \"unit\": \"lux\",\n  \"planes\": [\n"
            "    {\"name\": \"desks\", \"height\": 0.8, \"spacing\": 0.5, \"points\": 3, "
            "\"min\": 50, \"mean\": 150, \"max\": 300, \"uniformity_min_mean\": "
            "0.3333333333333333, \"uniformity_min_max\": 0.16666666666666666,\n"
            "     \"levels\": [\n"
            "       {\"surface_height\": 0, \"points\": 2, \"min\": 100, \"mean\": 200, "
            "\"max\": 300, \"uniformity_min_mean\": 0.5, \"uniformity_min_max\": "
            "0.3333333333333333},\n"
            "       {\"surface_height\": 3, \"points\": 1, \"min\": 50, \"mean\": 50, \"max\": 50, "
            "\"uniformity_min_mean\": 1, \"uniformity_min_max\": 1}\n"
            "     ]}\n  ]\n}\n");
  EXPECT_EQ(IlluminanceJson({}), "{\n  \"unit\": \"lux\",\n  \"planes\": []\n}\n");
}

TEST(IlluminanceReportTest, FilesAreWrittenPerPlaneBesideTheJson) {
  TestDir dir;
  ASSERT_TRUE(WriteIlluminanceFiles(dir.File(""), {TwoLevels()}).ok());
  EXPECT_EQ(ReadFileBytes(dir.File("illuminance.json")), IlluminanceJson({TwoLevels()}));
  EXPECT_EQ(ReadFileBytes(dir.File("illuminance/desks.csv")), IlluminanceCsv(TwoLevels()));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.File("illuminance/desks.png")));
  EXPECT_EQ(std::filesystem::directory_iterator(dir.File("illuminance")) ==
                std::filesystem::directory_iterator(),
            false);
  TestDir empty;
  ASSERT_TRUE(WriteIlluminanceFiles(empty.File(""), {}).ok());
  EXPECT_TRUE(empty.Entries().empty());
}

TEST(IlluminanceReportTest, AnUnwritableDirectoryIsReportedPerFile) {
  const Status s = WriteIlluminanceFiles("/proc/radfarm-no-such-dir", {TwoLevels()});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("illuminance"), std::string::npos) << s.error();
}

// Patches 0-1 of object "Desk 1" (material "wood"), 2-3 of "Floor" (material "tiles").
struct Named {
  PatchScene scene;
  std::vector<InputObject> objects;
  std::vector<uint32_t> patch_object = {0, 0, 1, 1};
};

Named NamedScene() {
  Named n;
  n.scene.patches.resize(4);
  n.scene.material_names = {"wood", "tiles"};
  for (uint32_t f = 0; f < 4; ++f) n.scene.patches[f].material = f / 2;
  n.objects.resize(2);
  n.objects[0].name = "Desk 1";
  n.objects[1].name = "Floor";
  return n;
}

TEST(IlluminancePlanesTest, SurfacesAreNamedByObjectOrMaterialPattern) {
  const Named n = NamedScene();
  const auto carries = [&](std::vector<std::string> surfaces) {
    Result<std::vector<bool>> r =
        SurfacesNamed({"p", 0.8, 1, std::move(surfaces)}, n.scene, n.objects, n.patch_object);
    EXPECT_TRUE(r.ok()) << r.error();
    return r.ok() ? *r : std::vector<bool>{};
  };
  EXPECT_EQ(carries({}), std::vector<bool>(4, true));
  EXPECT_EQ(carries({"Desk*"}), (std::vector<bool>{true, true, false, false}));
  EXPECT_EQ(carries({"tiles"}), (std::vector<bool>{false, false, true, true}));
  EXPECT_EQ(carries({"Floor", "wood"}), std::vector<bool>(4, true));
}

TEST(IlluminancePlanesTest, APatternNamingNothingIsAnError) {
  const Named n = NamedScene();
  Result<std::vector<bool>> r =
      SurfacesNamed({"desks", 0.8, 1, {"Desk*", "Tabel"}}, n.scene, n.objects, n.patch_object);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error(),
            "illuminance plane 'desks': 'Tabel' names no object and no material of the scene");
}

TEST(IlluminancePlaneTest, ProblemsNameTheKey) {
  EXPECT_EQ(IlluminancePlaneProblem({"desks", 0.8, 0.25, {"Desk*"}}), "");
  EXPECT_EQ(IlluminancePlaneProblem({"", 0.8, 0.25, {}}).rfind("name ", 0), 0u);
  EXPECT_EQ(IlluminancePlaneProblem({"../x", 0.8, 0.25, {}}).rfind("name ", 0), 0u);
  EXPECT_EQ(IlluminancePlaneProblem({"a", -1, 0.25, {}}), "height must be finite and >= 0");
  EXPECT_EQ(IlluminancePlaneProblem({"a", 1, 0, {}}), "spacing must be finite and > 0");
  EXPECT_EQ(IlluminancePlaneProblem({"a", 1, 1, {""}}), "surfaces must not hold an empty pattern");
}

}  // namespace
}  // namespace radfarm
