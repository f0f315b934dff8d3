#include "base/toml_table_reader.h"

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "base/toml_file.h"

namespace radfarm {
namespace {

const std::string kFile = "job.toml";

toml::table Parse(const std::string& text) {
  Result<toml::table> table = ParseToml(kFile, text);
  EXPECT_TRUE(table.ok()) << table.error();
  return table.ok() ? std::move(*table) : toml::table{};
}

TEST(TomlTableReaderTest, ReadsTypedKeysAndLeavesAbsentOnesAlone) {
  const toml::table table = Parse("a = 2\nb = 0.5\nc = \"x\"\nd = true\ne = [1, 2, 3.5]\n");
  TomlTableReader r(kFile, table, "");
  int64_t a = 0;
  double b = 0, missing = 9;
  std::string c;
  bool d = false, has_missing = true;
  std::array<double, 3> e{};
  EXPECT_TRUE(r.Integer("a", 0, 10, &a).ok());
  EXPECT_TRUE(r.Real("b", Interval::Open(0, 1), &b).ok());
  EXPECT_TRUE(r.String("c", &c).ok());
  EXPECT_TRUE(r.Bool("d", &d).ok());
  EXPECT_TRUE(r.Triple("e", &e).ok());
  EXPECT_TRUE(r.Real("f", Interval::Any(), &missing, &has_missing).ok());
  EXPECT_EQ(a, 2);
  EXPECT_EQ(b, 0.5);
  EXPECT_EQ(c, "x");
  EXPECT_TRUE(d);
  EXPECT_EQ(e, (std::array<double, 3>{1, 2, 3.5}));
  EXPECT_EQ(missing, 9);
  EXPECT_FALSE(has_missing);
  EXPECT_TRUE(r.CheckNoUnknownKeys().ok());
}

TEST(TomlTableReaderTest, ErrorsNameTheFileLineAndDottedKey) {
  const toml::table table = Parse("[solver]\n\ntolerance = 2\nrays = \"many\"\nup = [0, 1]\n");
  TomlTableReader root(kFile, table, "");
  Result<const toml::table*> solver = root.Table("solver");
  ASSERT_TRUE(solver.ok() && *solver != nullptr);
  TomlTableReader r(kFile, **solver, "solver.");
  double tolerance = 0;
  int64_t rays = 0;
  std::array<double, 3> up{};
  EXPECT_EQ(r.Real("tolerance", Interval::Open(0, 1), &tolerance).error(),
            "job.toml:3: 'solver.tolerance' must be in (0, 1), got 2");
  EXPECT_EQ(r.Integer("rays", 0, 10, &rays).error(),
            "job.toml:4: 'solver.rays' must be an integer, not a string");
  EXPECT_EQ(r.Triple("up", &up).error(),
            "job.toml:5: 'solver.up' must be an array of 3 finite numbers, e.g. [0, 1, 0]");
}

TEST(TomlTableReaderTest, ReportsTheFirstUnreadKeyByLine) {
  const toml::table table = Parse("known = 1\nzeta = 2\nalpha = 3\n");
  TomlTableReader r(kFile, table, "");
  int64_t known = 0;
  ASSERT_TRUE(r.Integer("known", 0, 5, &known).ok());
  EXPECT_EQ(r.CheckNoUnknownKeys().error(), "job.toml:2: unknown key 'zeta'");
}

}  // namespace
}  // namespace radfarm
