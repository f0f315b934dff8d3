// rebake.bin (solve/previous_solve.h): written and read back to the bit, and refused whole when
// its bytes are not what a render wrote.
#include "solve/previous_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/input/test_files.h"

namespace radfarm {
namespace {

using testing::WriteScratchFile;

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

PreviousSolve TwoPatches() {
  PreviousSolve s;
  s.geometry_hash = std::string(64, 'a');
  s.lamps_hash = std::string(64, '0');
  s.start_work = StartWork{11, 7, true, 32};
  PreviousPatchValues& v = s.values;
  v.radiosity = {{0.1, 0.2, 0.3}, {1.0 / 3, 2.5, 0}};
  v.unshot = {{-1e-9, 0, 1e-12}, {0, 0, 0}};
  v.emission = {{0, 0, 0}, {2, 2, 1.8}};
  v.reflectance = {{0.5, 0.4, 0.3}, {0, 0, 0}};
  v.direct = {{0.7, 0.7, 0.6}, {0, 0, 0}};
  v.emitters_direct = true;
  v.punctual_power = 0.25;
  return s;
}

TEST(PreviousSolveTest, RoundTripsToTheBit) {
  const std::string path = WriteScratchFile("rebake.bin", "");
  ASSERT_TRUE(WritePreviousSolve(path, TwoPatches()).ok());
  Result<PreviousSolve> read = ReadPreviousSolve(path);
  ASSERT_TRUE(read.ok()) << read.error();
  const PreviousSolve want = TwoPatches();
  EXPECT_EQ(read->geometry_hash, want.geometry_hash);
  EXPECT_EQ(read->lamps_hash, want.lamps_hash);
  EXPECT_EQ(read->start_work, want.start_work);
  EXPECT_EQ(read->values.radiosity, want.values.radiosity);
  EXPECT_EQ(read->values.unshot, want.values.unshot);
  EXPECT_EQ(read->values.emission, want.values.emission);
  EXPECT_EQ(read->values.reflectance, want.values.reflectance);
  EXPECT_EQ(read->values.direct, want.values.direct);
  EXPECT_TRUE(read->values.emitters_direct);
  EXPECT_EQ(read->values.punctual_power, 0.25);
}

TEST(PreviousSolveTest, WithoutADirectStartNoneIsRead) {
  PreviousSolve s = TwoPatches();
  s.start_work.reset();
  s.values.direct.clear();
  s.values.emitters_direct = false;
  const std::string path = WriteScratchFile("rebake.bin", "");
  ASSERT_TRUE(WritePreviousSolve(path, s).ok());
  Result<PreviousSolve> read = ReadPreviousSolve(path);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_FALSE(read->start_work.has_value());
  EXPECT_TRUE(read->values.direct.empty());
  EXPECT_FALSE(read->values.emitters_direct);
}

// The error of `bytes` read as rebake.bin.
std::string ErrorOf(const std::string& bytes) {
  Result<PreviousSolve> read = ReadPreviousSolve(WriteScratchFile("bad.bin", bytes));
  return read.ok() ? "" : read.error();
}

TEST(PreviousSolveTest, BrokenFilesAreRefusedWithTheReason) {
  const std::string path = WriteScratchFile("rebake.bin", "");
  PreviousSolve s = TwoPatches();
  ASSERT_TRUE(WritePreviousSolve(path, s).ok());
  const std::string good = FileBytes(path);
  EXPECT_NE(ErrorOf("PLY\n" + good.substr(4)).find("not a re-bake file"), std::string::npos);
  std::string version = good;
  version[8] = 9;
  EXPECT_NE(ErrorOf(version).find("version 9"), std::string::npos) << ErrorOf(version);
  EXPECT_NE(ErrorOf(good + "x").find("patches take"), std::string::npos);
  s.values.radiosity[1].g = NAN;
  ASSERT_TRUE(WritePreviousSolve(path, s).ok());
  EXPECT_NE(ErrorOf(FileBytes(path)).find("patch 1: a value is not finite"), std::string::npos);
  s = TwoPatches();
  s.values.reflectance[0].r = 1;
  ASSERT_TRUE(WritePreviousSolve(path, s).ok());
  EXPECT_NE(ErrorOf(FileBytes(path)).find("patch 0: reflectance outside"), std::string::npos);
}

}  // namespace
}  // namespace radfarm
