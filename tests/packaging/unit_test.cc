// The systemd units as installed: `systemd-analyze verify` on an install tree (cmake --install
// with DESTDIR, beside a copy of the host's own units, which verify needs for the targets ours
// name) and `systemd-analyze security --offline=true` exposure, which docs/OPERATIONS.md records.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "shell.h"

namespace radfarm::packaging {
namespace {

namespace fs = std::filesystem;
using testing::HaveTool;
using testing::Quote;
using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

constexpr const char* kUnits[] = {"radfarmd.service", "radfarm-agent.service"};

bool Packaged(const std::string& binary) {
  std::istringstream list(RADFARM_PACKAGED_BINARIES);
  for (std::string name; std::getline(list, name, ',');) {
    if (name == binary) return true;
  }
  return false;
}

fs::path HostUnitDir() {
  for (const char* dir : {"/lib/systemd/system", "/usr/lib/systemd/system"}) {
    if (fs::exists(fs::path(dir) / "sysinit.target")) return dir;
  }
  return {};
}

// DESTDIR=root cmake --install BUILD --prefix /usr, both components.
void InstallInto(const fs::path& root) {
  for (const char* component : {"master", "agent"}) {
    const testing::CommandResult install =
        RunCommand("DESTDIR=" + Quote(root) + " " + Quote(RADFARM_CMAKE_COMMAND) + " --install " +
                   Quote(RADFARM_BINARY_DIR) + " --prefix /usr --component " + component);
    ASSERT_EQ(install.exit_code, 0) << install.output;
  }
}

TEST(UnitTest, SystemdAnalyzeVerifiesTheInstalledUnits) {
  if (!HaveTool("systemd-analyze")) GTEST_SKIP() << "systemd-analyze is not installed (systemd)";
  const fs::path host_units = HostUnitDir();
  if (host_units.empty()) GTEST_SKIP() << "no systemd units on this machine to verify against";

  TempDir root;
  ASSERT_FALSE(root.path().empty());
  ASSERT_NO_FATAL_FAILURE(InstallInto(root.path()));
  fs::create_directories(root.path() / "lib/systemd");
  fs::copy(host_units, root.path() / "lib/systemd/system",
           fs::copy_options::recursive | fs::copy_options::copy_symlinks |
               fs::copy_options::skip_existing);
  // verify checks that ExecStart= is executable. A daemon this build does not have yet gets an
  // executable in its place, so its unit is still checked line by line.
  for (const char* binary : {"radfarmd", "radfarm-agent"}) {
    const fs::path path = root.path() / "usr/bin" / binary;
    if (Packaged(binary)) {
      EXPECT_TRUE(fs::exists(path)) << path;
      continue;
    }
    std::cout << "note: " << binary << " is not part of this build; verifying its unit against "
              << "an executable placeholder\n";
    fs::create_directories(path.parent_path());
    { std::ofstream(path) << "#!/bin/sh\nexit 1\n"; }
    fs::permissions(path, fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
  }

  for (const char* unit : kUnits) {
    SCOPED_TRACE(unit);
    ASSERT_TRUE(fs::exists(root.path() / "usr/lib/systemd/system" / unit));
    // Any output is a finding (an unknown key is only a warning, with exit code 0).
    const testing::CommandResult verify =
        RunCommand("systemd-analyze verify --man=no --root=" + Quote(root.path()) + " " + unit);
    EXPECT_EQ(verify.exit_code, 0) << verify.output;
    EXPECT_EQ(verify.output, "");
  }
}

// The value of the unit file line `key=VALUE` ("" when there is none).
std::string UnitSetting(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(key + "=", 0) == 0) return line.substr(key.size() + 1);
  }
  return "";
}

// A daemon's exit status for a config file it cannot read.
int ExitStatusOnMissingConfig(const std::string& binary) {
  TempDir dir;
  return RunCommand(Quote(binary) + " --config " + Quote(dir.path() / "missing.conf")).exit_code;
}

// A config error is bad input (exit status 2 in both daemons), which a restart cannot fix: each
// unit restarts on failure but not on that status, so a typo does not restart-loop forever.
TEST(UnitTest, UnitsDoNotRestartOnBadInput) {
  constexpr int kExitBadInput = 2;  // agent/exit_codes.h, daemon/main.cc
  for (const char* unit : kUnits) {
    SCOPED_TRACE(unit);
    const std::string text = ReadFile(fs::path(RADFARM_SOURCE_DIR) / "systemd" / unit);
    EXPECT_EQ(UnitSetting(text, "Restart"), "on-failure");
    EXPECT_EQ(UnitSetting(text, "RestartPreventExitStatus"), std::to_string(kExitBadInput));
  }
#ifdef RADFARMD_PATH
  EXPECT_EQ(ExitStatusOnMissingConfig(RADFARMD_PATH), kExitBadInput);
#endif
#ifdef RADFARM_AGENT_PATH
  EXPECT_EQ(ExitStatusOnMissingConfig(RADFARM_AGENT_PATH), kExitBadInput);
#endif
}

// "→ Overall exposure level for radfarmd.service: 1.1 OK 🙂" -> "1.1"
std::string Exposure(const std::string& output, const std::string& unit) {
  std::smatch match;
  const std::regex pattern("Overall exposure level for " +
                           std::regex_replace(unit, std::regex("\\."), "\\.") +
                           ": ([0-9]+\\.[0-9])");
  return std::regex_search(output, match, pattern) ? match[1].str() : "";
}

TEST(UnitTest, SecurityExposureIsLowAndRecordedInOperations) {
  if (!HaveTool("systemd-analyze")) GTEST_SKIP() << "systemd-analyze is not installed (systemd)";
  const std::string operations = ReadFile(fs::path(RADFARM_SOURCE_DIR) / "docs/OPERATIONS.md");
  for (const char* unit : kUnits) {
    SCOPED_TRACE(unit);
    const fs::path path = fs::path(RADFARM_SOURCE_DIR) / "systemd" / unit;
    // --threshold=20: exit code 1 above an exposure of 2.0.
    const testing::CommandResult security =
        RunCommand("cd / && systemd-analyze security --offline=true --threshold=20 " + Quote(path));
    EXPECT_EQ(security.exit_code, 0) << security.output;
    const std::string exposure = Exposure(security.output, unit);
    ASSERT_FALSE(exposure.empty()) << security.output;
    std::cout << unit << ": exposure " << exposure << "\n";
    const std::string recorded = "| `" + std::string(unit) + "` | " + exposure + " |";
    EXPECT_NE(operations.find(recorded), std::string::npos)
        << "docs/OPERATIONS.md should record the measured score: " << recorded;
  }
}

}  // namespace
}  // namespace radfarm::packaging
