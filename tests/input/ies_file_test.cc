// input/ies_file.h: the LM-63 formats as manufacturers publish them, and every way a file can be
// wrong, each error naming the file and line.
#include "input/ies_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "base/text_file.h"
#include "tests/input/test_files.h"

namespace radfarm {
namespace {

using testing::DataPath;

Result<IesPhotometry> ParseData(const std::string& name) {
  const std::string path = DataPath("ies/" + name);
  Result<std::string> text = ReadTextFile(path);
  if (!text) return Error{text.error()};
  return ParseIes(*text, path);
}

// The header a test of one broken field starts from: a two-angle table after it.
std::string Header(const std::string& numbers) {
  return "IESNA:LM-63-2002\n[MANUFAC] Test\nTILT=NONE\n" + numbers;
}

std::string ErrorOf(const std::string& text) {
  Result<IesPhotometry> ies = ParseIes(text, "lamp.ies");
  return ies ? std::string("(parsed)") : ies.error();
}

TEST(IesFile, ReadsAManufacturersLm63_2002Downlight) {
  Result<IesPhotometry> ies = ParseData("downlight_lm63_2002.ies");
  ASSERT_TRUE(ies) << ies.error();
  EXPECT_EQ(ies->format, "LM-63-2002");
  ASSERT_EQ(ies->keywords.size(), 11u);
  EXPECT_EQ(ies->keywords[3].first, "MANUFAC");
  EXPECT_EQ(ies->keywords[3].second, "Example Lighting Ltd");
  EXPECT_EQ(ies->lamps, 1);
  EXPECT_EQ(ies->lumens_per_lamp, -1);
  EXPECT_EQ(ies->input_watts, 18);
  EXPECT_DOUBLE_EQ(ies->width, -0.15);  // a round opening, 150 mm across
  ASSERT_EQ(ies->table.vertical.size(), 19u);
  ASSERT_EQ(ies->table.horizontal.size(), 1u);
  EXPECT_EQ(ies->table.candela.front(), 1000.0);
  EXPECT_EQ(ies->table.candela.back(), 0.0);
  // 1000 cd cos(theta) over the lower hemisphere: pi 1000 lm, less what the 5-degree chords
  // and the table's rounding to 0.1 cd leave out.
  EXPECT_NEAR(TableLumens(ies->table), std::numbers::pi * 1000, 3.0);
}

TEST(IesFile, ReadsLm63_1995InFeetWithMultiplierAndBallastFactor) {
  Result<IesPhotometry> ies = ParseData("wallwasher_lm63_1995.ies");
  ASSERT_TRUE(ies) << ies.error();
  EXPECT_EQ(ies->format, "LM-63-1995");
  // The free text line of a 1995 header is kept without a keyword.
  ASSERT_EQ(ies->keywords.size(), 6u);
  EXPECT_EQ(ies->keywords[5].first, "");
  EXPECT_EQ(ies->lamps, 2);
  EXPECT_EQ(ies->lumens_per_lamp, 2600);
  EXPECT_DOUBLE_EQ(ies->length, 2.0 * 0.3048);
  EXPECT_DOUBLE_EQ(ies->ballast_factor, 0.9);
  // 800 cd in the file, times the multiplier 0.5 and the ballast factor 0.9.
  EXPECT_DOUBLE_EQ(ies->table.candela[0], 800 * 0.5 * 0.9);
  EXPECT_DOUBLE_EQ(CandelaAt(ies->table, 30, 90), 300 * 0.5 * 0.9);
  // Quadrant symmetry: 135 degrees reads the 45 plane, 270 the 90 plane.
  EXPECT_DOUBLE_EQ(CandelaAt(ies->table, 30, 135), CandelaAt(ies->table, 30, 45));
  EXPECT_DOUBLE_EQ(CandelaAt(ies->table, 60, 270), 200 * 0.5 * 0.9);
}

TEST(IesFile, ReadsEveryPlaneOfAnAsymmetricLuminaire) {
  Result<IesPhotometry> ies = ParseData("asymmetric_lm63_2002.ies");
  ASSERT_TRUE(ies) << ies.error();
  EXPECT_DOUBLE_EQ(CandelaAt(ies->table, 0, 180), 300);
  EXPECT_DOUBLE_EQ(CandelaAt(ies->table, 45, 270), 320);
  EXPECT_DOUBLE_EQ(CandelaAt(ies->table, 0, 315), 250);  // halfway from 400 at 270 to 100 at 360
}

TEST(IesFile, AcceptsNumbersSplitAcrossLinesAndCommas) {
  Result<IesPhotometry> ies =
      ParseIes(Header("1 -1 1\n2 1 1 2 0 0 0\n1 1 5\n0,90\n0\n100,\n0\n"), "lamp.ies");
  ASSERT_TRUE(ies) << ies.error();
  EXPECT_DOUBLE_EQ(CandelaAt(ies->table, 45, 10), 50);
}

TEST(IesFile, NamesTheFileAndLineOfEachError) {
  EXPECT_EQ(ErrorOf("IESNA:LM-63-2019\nTILT=NONE\n"),
            "lamp.ies:1: 'IESNA:LM-63-2019' is not an LM-63 header: expected IESNA:LM-63-2002, "
            "IESNA:LM-63-1995 or IESNA91");
  EXPECT_EQ(ErrorOf("IESNA:LM-63-2002\n[MANUFAC] x\n"), "lamp.ies:2: the file has no TILT line");
  EXPECT_EQ(ErrorOf("IESNA:LM-63-2002\nfree text\nTILT=NONE\n"),
            "lamp.ies:2: 'free text' is neither a [KEYWORD] line nor the TILT line, as "
            "LM-63-2002 requires");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 0\n1 1 5\n0 90\n0\n100 abc\n")),
            "lamp.ies:8: a value of the candela table 'abc' is not a number");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 0\n1 1 5\n0 90\n0\n100\n")),
            "lamp.ies:8: the file ends inside the candela table (1 of 2 values)");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 0\n1 1 5\n0 90\n0\n100 0\n7\n")),
            "lamp.ies:9: unexpected '7' after the candela table");
}

TEST(IesFile, RefusesWhatItCannotModel) {
  EXPECT_EQ(ErrorOf("IESNA:LM-63-2002\nTILT=INCLUDE\n"),
            "lamp.ies:2: TILT=INCLUDE is not supported: the luminaire's output must not depend "
            "on its tilt (TILT=NONE)");
  EXPECT_EQ(ErrorOf("IESNA:LM-63-1995\nTILT=lamp.tlt\n"),
            "lamp.ies:2: TILT=lamp.tlt names a tilt file, which is not supported: only "
            "TILT=NONE");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 2 2 0 0 0\n")),
            "lamp.ies:4: photometric type 2 (type B) is not supported: only type C (1)");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 3 2 0 0 0\n")),
            "lamp.ies:4: photometric type 3 (type A) is not supported: only type C (1)");
}

TEST(IesFile, ChecksEveryNumber) {
  EXPECT_EQ(ErrorOf(Header("0 -1 1 2 1 1 2 0 0 0\n")),
            "lamp.ies:4: the lamp count 0 is not a whole number from 1 to 1000");
  EXPECT_EQ(ErrorOf(Header("1 0 1 2 1 1 2 0 0 0\n")),
            "lamp.ies:4: the lumens per lamp 0 is neither positive nor -1 (absolute photometry)");
  EXPECT_EQ(ErrorOf(Header("1 -1 -2 2 1 1 2 0 0 0\n")),
            "lamp.ies:4: the candela multiplier -2 is not positive");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2.5 1 1 2 0 0 0\n")),
            "lamp.ies:4: the number of vertical angles 2.5 is not a whole number from 1 to 10000");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 3 0 0 0\n")),
            "lamp.ies:4: the units type (1 feet, 2 metres) 3 is not a whole number from 1 to 2");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 nan\n")),
            "lamp.ies:4: the luminous opening's size 'nan' is not a number");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 0\n0 1 5\n")),
            "lamp.ies:5: the ballast factor 0 is not positive");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 0\n1 1 -5\n")),
            "lamp.ies:5: the input watts -5 is negative");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 0\n1 1 5\n0 90\n0\n100 -1\n")),
            "lamp.ies:8: the candela table holds a negative value -1");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 1 1 2 0 0 0\n1 1 5\n90 0\n0\n100 0\n")),
            "lamp.ies:6: the vertical angles are not strictly increasing");
  EXPECT_EQ(ErrorOf(Header("1 -1 1 2 2 1 2 0 0 0\n1 1 5\n0 90\n0 45\n1 2 3 4\n")),
            "lamp.ies:7: the horizontal angles are not 0 alone, 0 to 90, 0 to 180, 90 to 270 or "
            "0 to 360");
}

}  // namespace
}  // namespace radfarm
