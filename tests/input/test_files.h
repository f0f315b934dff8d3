// Paths of test data and scenes, and scratch files for tests that need exact bytes.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/rgb.h"

namespace radfarm::testing {

inline std::string DataPath(const std::string& name) {
  return std::string(RADFARM_SOURCE_DIR) + "/tests/input/data/" + name;
}

inline std::string ScenePath(const std::string& name) {
  return std::string(RADFARM_SOURCE_DIR) + "/scenes/" + name;
}

// Writes `content` to a fresh file under the test's temporary directory and returns its path.
inline std::string WriteScratchFile(const std::string& name, const std::string& content) {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / (std::string("radfarm_input_") + test->name());
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / name;
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

// tinyobjloader's own decimal parser can land one ulp away from the nearest double (0.725 reads as
// 0.72500000000000009), so decimal values from files are compared to within a few ulps.
inline ::testing::AssertionResult RgbNear(const Rgb& actual, const Rgb& expected) {
  const ::testing::internal::FloatingPoint<double> r(actual.r), g(actual.g), b(actual.b);
  if (r.AlmostEquals(::testing::internal::FloatingPoint<double>(expected.r)) &&
      g.AlmostEquals(::testing::internal::FloatingPoint<double>(expected.g)) &&
      b.AlmostEquals(::testing::internal::FloatingPoint<double>(expected.b))) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << "(" << actual.r << ", " << actual.g << ", " << actual.b << ") is not (" << expected.r
         << ", " << expected.g << ", " << expected.b << ")";
}

}  // namespace radfarm::testing
