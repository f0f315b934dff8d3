// cpack -G DEB builds radfarm-master and radfarm-agent; dpkg-deb shows what they hold. Built once
// for all the checks (cpack runs the build's preinstall step, a no-op on a built tree).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "shell.h"

namespace radfarm::packaging {
namespace {

using testing::HaveTool;
using testing::Quote;
using testing::ReadFile;
using testing::RunCommand;
using testing::TempDir;

std::set<std::string> PackagedBinaries() {
  std::set<std::string> binaries;
  std::istringstream list(RADFARM_PACKAGED_BINARIES);
  for (std::string name; std::getline(list, name, ',');) {
    if (!name.empty()) binaries.insert(name);
  }
  return binaries;
}

// The paths in `dpkg-deb -c` output, without the leading "." ("/usr/bin/radfarm").
std::set<std::string> Contents(const std::string& deb) {
  std::set<std::string> paths;
  std::istringstream lines(RunCommand("dpkg-deb -c " + Quote(deb)).output);
  for (std::string line; std::getline(lines, line);) {
    const size_t dot = line.find(" ./");
    if (dot == std::string::npos) continue;
    std::string path = line.substr(dot + 2);
    if (path.size() > 1 && path.back() == '/') continue;  // directories
    paths.insert(path);
  }
  return paths;
}

struct Package {
  std::string name;
  std::string deb;
  std::vector<std::string> binaries;  // the build targets that go into it
  std::vector<std::string> files;     // and the other files it must hold
  std::string user;
  std::string state_dir;
};

std::vector<Package> Packages(const std::filesystem::path& out) {
  const std::string arch = RunCommand("dpkg --print-architecture").output;
  const std::string suffix = "_0.1.0_" + arch.substr(0, arch.find('\n')) + ".deb";
  return {
      {"radfarm-master",
       (out / ("radfarm-master" + suffix)).string(),
       {"radfarmd", "radfarm"},
       {"/usr/lib/systemd/system/radfarmd.service", "/etc/radfarm/radfarmd.conf",
        "/usr/share/doc/radfarm-master/OPERATIONS.md", "/usr/share/doc/radfarm-master/CONTROL.md"},
       "radfarm",
       "/var/lib/radfarm"},
      {"radfarm-agent",
       (out / ("radfarm-agent" + suffix)).string(),
       {"radfarm-agent"},
       {"/usr/lib/systemd/system/radfarm-agent.service", "/etc/radfarm/agent.conf",
        "/usr/share/doc/radfarm-agent/OPERATIONS.md",
        "/usr/share/doc/radfarm-agent/examples/radfarm-agent.htcondor.sub",
        "/usr/share/doc/radfarm-agent/examples/radfarm-agent.slurm.sh"},
       "radfarm-agent",
       "/var/lib/radfarm-agent"},
  };
}

bool HoldsABinary(const Package& package) {
  const std::set<std::string> built = PackagedBinaries();
  return std::any_of(package.binaries.begin(), package.binaries.end(),
                     [&](const std::string& binary) { return built.count(binary) > 0; });
}

void ExpectExactlyItsFiles(const Package& package) {
  const std::set<std::string> built = PackagedBinaries();
  std::set<std::string> expected(package.files.begin(), package.files.end());
  for (const std::string& binary : package.binaries) {
    if (built.count(binary)) expected.insert("/usr/bin/" + binary);
  }
  EXPECT_EQ(Contents(package.deb), expected) << "dpkg-deb -c " << package.deb;
}

void ExpectControlFields(const Package& package) {
  const auto field = [&](const std::string& name) {
    std::string value = RunCommand("dpkg-deb -f " + Quote(package.deb) + " " + name).output;
    while (!value.empty() && value.back() == '\n') value.pop_back();
    return value;
  };
  EXPECT_EQ(field("Package"), package.name);
  EXPECT_EQ(field("Version"), "0.1.0");
  const std::string depends = field("Depends");
  EXPECT_NE(depends.find("adduser"), std::string::npos) << depends;
  // dpkg-shlibdeps found the libraries the binaries link.
  if (HoldsABinary(package)) {
    EXPECT_NE(depends.find("libc6"), std::string::npos) << depends;
  }
}

void ExpectConfigsAreConffiles(const Package& package) {
  const testing::CommandResult conffiles =
      RunCommand("dpkg-deb -I " + Quote(package.deb) + " conffiles");
  ASSERT_EQ(conffiles.exit_code, 0) << conffiles.output;
  std::string expected;
  for (const std::string& file : package.files) {
    if (file.rfind("/etc/", 0) == 0) expected += file + "\n";
  }
  EXPECT_EQ(conffiles.output, expected);
}

// `script` without its comment lines.
std::string CodeLines(const std::string& script) {
  std::istringstream lines(script);
  std::string code;
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line[first] == '#') continue;
    code += line + "\n";
  }
  return code;
}

void ExpectScriptsCreateTheUserAndStartNothing(const Package& package) {
  TempDir control;
  const testing::CommandResult extracted =
      RunCommand("dpkg-deb -e " + Quote(package.deb) + " " + Quote(control.path() / "DEBIAN"));
  ASSERT_EQ(extracted.exit_code, 0) << extracted.output;
  for (const char* script : {"postinst", "prerm", "postrm"}) {
    SCOPED_TRACE(script);
    const auto path = control.path() / "DEBIAN" / script;
    struct stat info {};
    ASSERT_EQ(stat(path.c_str(), &info), 0);
    EXPECT_EQ(info.st_mode & 0777, 0755u);
    const testing::CommandResult syntax = RunCommand("sh -n " + Quote(path));
    EXPECT_EQ(syntax.exit_code, 0) << syntax.output;
    const std::string text = CodeLines(ReadFile(path));
    // Nothing is enabled or started: only the administrator does that. (try-restart on an
    // upgrade restarts a running unit and leaves a stopped one stopped.)
    for (const char* forbidden : {"systemctl start", "systemctl enable", "systemctl restart",
                                  "systemctl reload-or-restart", "--now", "deb-systemd-invoke",
                                  "deb-systemd-helper enable", "invoke-rc.d", "update-rc.d"}) {
      EXPECT_EQ(text.find(forbidden), std::string::npos) << forbidden << " in\n" << text;
    }
  }
  const std::string postinst = ReadFile(control.path() / "DEBIAN" / "postinst");
  EXPECT_NE(postinst.find("adduser --quiet --system --group"), std::string::npos) << postinst;
  EXPECT_NE(postinst.find("install -d -o " + package.user + " -g " + package.user + " -m 0750 " +
                          package.state_dir),
            std::string::npos)
      << postinst;
  const std::string postrm = ReadFile(control.path() / "DEBIAN" / "postrm");
  EXPECT_NE(postrm.find("rm -rf " + package.state_dir), std::string::npos) << postrm;
}

// One test: cpack runs once (it also runs the build's preinstall step, a no-op on a built tree).
TEST(PackageTest, CpackBuildsTheMasterAndAgentPackages) {
  for (const char* tool : {"dpkg-deb", "dpkg-shlibdeps", "file"}) {
    if (!HaveTool(tool))
      GTEST_SKIP() << tool << " is not installed (packages dpkg, dpkg-dev, file)";
  }
  TempDir out;
  ASSERT_FALSE(out.path().empty());
  const testing::CommandResult cpack =
      RunCommand(std::string(RADFARM_CPACK_COMMAND) + " -G DEB -B " + Quote(out.path()) +
                 " --config " + Quote(std::string(RADFARM_BINARY_DIR) + "/CPackConfig.cmake"));
  ASSERT_EQ(cpack.exit_code, 0) << cpack.output;

  for (const Package& package : Packages(out.path())) {
    SCOPED_TRACE(package.name);
    ExpectExactlyItsFiles(package);
    ExpectControlFields(package);
    ExpectConfigsAreConffiles(package);
    ExpectScriptsCreateTheUserAndStartNothing(package);
  }
}

}  // namespace
}  // namespace radfarm::packaging
