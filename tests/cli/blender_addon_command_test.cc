// `radfarm blender-addon install`: the packaged add-on found beside the program, Blender's
// add-ons folder from the environment, and a copy that replaces an earlier one whole.
#include "cli/blender_addon_command.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

namespace fs = std::filesystem;
using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

void Write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

EnvLookup Env(std::map<std::string, std::string> values) {
  return [values](const std::string& name) -> std::optional<std::string> {
    auto it = values.find(name);
    if (it == values.end()) return std::nullopt;
    return it->second;
  };
}

std::vector<std::string> Names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(BlenderAddonCommandTest, FindsTheAddonBesideTheProgram) {
  TempDir dir;
  const fs::path prefix = dir.path();
  Write(prefix / "share/radfarm/blender/radfarm_bake/__init__.py", "bl_info = {}\n");
  Result<fs::path> found = PackagedAddon(prefix / "bin" / "radfarm");
  ASSERT_TRUE(found.ok()) << found.error();
  EXPECT_EQ(*found, prefix / "share/radfarm/blender/radfarm_bake");

  Result<fs::path> missing = PackagedAddon(prefix / "elsewhere" / "x" / "radfarm");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().find(prefix.string() + "/elsewhere/share/radfarm/blender/"
                                                   "radfarm_bake/__init__.py"),
            std::string::npos)
      << missing.error();
}

TEST(BlenderAddonCommandTest, AddonsFolderFromBlendersEnvironment) {
  EXPECT_EQ(*DefaultAddonsDir(Env({{"BLENDER_USER_SCRIPTS", "/s"}, {"HOME", "/h"}})), "/s/addons");
  EXPECT_EQ(*DefaultAddonsDir(Env({{"XDG_CONFIG_HOME", "/x"}, {"HOME", "/h"}})),
            "/x/blender/3.4/scripts/addons");
  EXPECT_EQ(*DefaultAddonsDir(Env({{"HOME", "/h"}})), "/h/.config/blender/3.4/scripts/addons");
  Result<fs::path> none = DefaultAddonsDir(Env({}));
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().find("--addons-dir"), std::string::npos) << none.error();
}

TEST(BlenderAddonCommandTest, InstallReplacesAnEarlierCopyWhole) {
  TempDir dir;
  const fs::path source = fs::path(dir.path()) / "src";
  Write(source / "__init__.py", "new init\n");
  Write(source / "apply.py", "new apply\n");
  Write(source / "__pycache__/apply.cpython-311.pyc", "cache");
  Write(source / kAddonProgramFile, "/not/this/radfarm\n");
  const fs::path addons = fs::path(dir.path()) / "config/scripts/addons";
  Write(addons / kAddonName / "__init__.py", "old init\n");
  Write(addons / kAddonName / "gone.py", "a module the new version no longer has\n");
  Write(addons / "other_addon.py", "someone else's\n");

  Status installed = InstallAddon(source, addons, "/opt/radfarm/bin/radfarm");
  ASSERT_TRUE(installed.ok()) << installed.error();
  const fs::path target = addons / kAddonName;
  EXPECT_EQ(Names(target),
            (std::vector<std::string>{"__init__.py", "apply.py", kAddonProgramFile}));
  EXPECT_EQ(ReadFile(target / "__init__.py"), "new init\n");
  EXPECT_EQ(ReadFile(target / kAddonProgramFile), "/opt/radfarm/bin/radfarm\n");
  EXPECT_EQ(Names(addons), (std::vector<std::string>{"other_addon.py", kAddonName}))
      << "a temporary folder was left behind, or another add-on touched";
}

TEST(BlenderAddonCommandTest, InstallIntoAFileFailsAndSaysWhere) {
  TempDir dir;
  const fs::path source = fs::path(dir.path()) / "src";
  Write(source / "__init__.py", "init\n");
  Write(fs::path(dir.path()) / "a_file", "not a folder\n");
  Status installed = InstallAddon(source, fs::path(dir.path()) / "a_file" / "addons", "radfarm");
  ASSERT_FALSE(installed.ok());
  EXPECT_NE(installed.error().find("a_file/addons"), std::string::npos) << installed.error();
}

TEST(BlenderAddonCommandTest, TheCommandInstallsTheBuildTreesAddon) {
  TempDir dir;
  const fs::path program = fs::canonical(RADFARM_CLI_PATH);
  const auto printed = RunCommand({RADFARM_CLI_PATH, "blender-addon", "install", "--print-path"});
  ASSERT_EQ(printed.exit_code, kExitOk) << printed.err;
  const fs::path packaged = printed.out.substr(0, printed.out.find('\n'));
  EXPECT_TRUE(fs::is_regular_file(packaged / "__init__.py")) << printed.out;

  // Without --addons-dir: Blender's own variable says where.
  const auto r = RunCommand({RADFARM_CLI_PATH, "blender-addon", "install"},
                            {"BLENDER_USER_SCRIPTS=" + dir.path() + "/scripts"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const fs::path target = fs::path(dir.path()) / "scripts/addons" / kAddonName;
  EXPECT_NE(r.out.find(target.string()), std::string::npos) << r.out;
  EXPECT_EQ(ReadFile(target / "__init__.py"), ReadFile(packaged / "__init__.py"));
  EXPECT_EQ(ReadFile(target / kAddonProgramFile), program.string() + "\n");
}

TEST(BlenderAddonCommandTest, TheCommandNamesAFolderItCannotMake) {
  TempDir dir;
  Write(fs::path(dir.path()) / "a_file", "x");
  const auto r = RunCommand({RADFARM_CLI_PATH, "blender-addon", "install", "--addons-dir",
                             dir.path() + "/a_file/addons"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("radfarm: " + dir.path() + "/a_file/addons"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace radfarm
