// The include-dependency check: every #include "..." of the tree against the table printed in
// docs/ARCHITECTURE.md ("Dependencies"), and unit checks that the check can fail.
#include "tests/architecture/include_rules.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace radfarm::architecture {
namespace {

constexpr const char* kTable = R"(Some prose.
<!-- deps:begin -->
| Folder | May include |
| --- | --- |
| `base/` | — |
| `core/` | — |
| `input/` | `base/`, `core/` |
| `daemon/` | `base/`, `daemon/store/` |
| `daemon/store/` | `base/` |
<!-- deps:end -->
More prose.
)";

const std::set<std::string> kFolders = {"base", "core", "input", "daemon", "docs"};

DependencyTable Table() {
  Result<DependencyTable> table = ParseDependencyTable(kTable);
  EXPECT_TRUE(table.ok()) << table.error();
  return table.ok() ? *table : DependencyTable{};
}

std::vector<std::string> Check(std::string_view path, std::string_view text) {
  std::vector<std::string> messages;
  for (const Violation& v : CheckFile(Table(), kFolders, path, text)) {
    messages.push_back(v.Describe());
  }
  return messages;
}

TEST(IncludeRulesTest, ParsesTheTableBetweenTheMarkers) {
  const DependencyTable table = Table();
  ASSERT_EQ(table.size(), 5u);
  EXPECT_TRUE(table.at("base").empty());
  EXPECT_EQ(table.at("input"), (std::set<std::string>{"base", "core"}));
  EXPECT_EQ(table.at("daemon"), (std::set<std::string>{"base", "daemon/store"}));
}

TEST(IncludeRulesTest, ReportsAForbiddenEdgeWithFileLineAndEdge) {
  EXPECT_EQ(Check("input/obj.cc", "#include \"input/obj.h\"\n\n#include \"daemon/master.h\"\n"),
            std::vector<std::string>{
                "input/obj.cc:3: input/ may not include daemon/ (#include \"daemon/master.h\")"});
  // An upward include from a subfolder to its parent folder is an edge too.
  EXPECT_EQ(Check("daemon/store/db.cc", "#include \"daemon/master.h\"\n"),
            std::vector<std::string>{"daemon/store/db.cc:1: daemon/store/ may not include daemon/ "
                                     "(#include \"daemon/master.h\")"});
}

TEST(IncludeRulesTest, AllowsTheTablesEdgesTheFoldersOwnAndThirdPartyHeaders) {
  EXPECT_TRUE(Check("input/obj.cc",
                    "#include \"input/obj.h\"\n#include <vector>\n#include \"base/result.h\"\n"
                    "  #  include \"core/vec3.h\"\n#include \"toml++/toml.h\"\n"
                    "#include \"frame_generated.h\"\n")
                  .empty());
  EXPECT_TRUE(Check("daemon/master.cc", "#include \"daemon/store/db.h\"\n").empty());
}

TEST(IncludeRulesTest, FoldersWithoutARowAreReported) {
  EXPECT_EQ(Check("docs/example.cc", "#include \"base/result.h\"\n"),
            std::vector<std::string>{
                "docs/example.cc: its folder has no row in docs/ARCHITECTURE.md's dependency "
                "table"});
  EXPECT_EQ(
      Check("input/obj.cc", "#include \"docs/x.h\"\n"),
      std::vector<std::string>{
          "input/obj.cc:1: includes a folder with no row in the table (#include \"docs/x.h\")"});
}

TEST(IncludeRulesTest, RejectsMalformedTables) {
  EXPECT_FALSE(ParseDependencyTable("| Folder | May include |\n| `a/` | — |\n").ok());
  const Result<DependencyTable> unknown = ParseDependencyTable(
      "<!-- deps:begin -->\n| Folder | May include |\n|---|---|\n| `a/` | `b/` |\n"
      "<!-- deps:end -->\n");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error(), "'a/' may include 'b/', which has no row");
  EXPECT_FALSE(ParseDependencyTable("<!-- deps:begin -->\n| Folder | May include |\n|---|---|\n"
                                    "| `a/` | — |\n| `a/` | — |\n<!-- deps:end -->\n")
                   .ok());
}

TEST(IncludeRulesTest, FindsACycleInTheTable) {
  EXPECT_EQ(FindCycle(Table()), std::nullopt);
  DependencyTable cyclic = Table();
  cyclic["daemon/store"].insert("input");
  cyclic["input"].insert("daemon");
  EXPECT_EQ(FindCycle(cyclic), "daemon -> daemon/store -> input -> daemon");
}

// The real check: the tree's includes against docs/ARCHITECTURE.md's table.
TEST(ArchitectureTest, EveryIncludeFollowsTheDependencyTable) {
  const std::filesystem::path root = RADFARM_SOURCE_DIR;
  std::ifstream in(root / "docs" / "ARCHITECTURE.md", std::ios::binary);
  ASSERT_TRUE(in) << "cannot read docs/ARCHITECTURE.md";
  std::ostringstream doc;
  doc << in.rdbuf();
  Result<DependencyTable> table = ParseDependencyTable(doc.str());
  ASSERT_TRUE(table.ok()) << "docs/ARCHITECTURE.md: " << table.error();
  EXPECT_EQ(FindCycle(*table), std::nullopt) << "the table allows a cycle";
  const std::vector<Violation> violations = CheckTree(*table, root);
  for (const Violation& v : violations) ADD_FAILURE() << v.Describe();
  EXPECT_TRUE(violations.empty()) << violations.size() << " includes break the table";
}

}  // namespace
}  // namespace radfarm::architecture
