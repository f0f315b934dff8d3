// cpack -G DEB builds radfarm (the CLI), radfarm-master and radfarm-agent; dpkg-deb shows what they
// hold and lintian checks them against Debian policy. Built once for all the checks.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <map>
#include <regex>
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
  const std::string suffix =
      std::string("_") + RADFARM_DEB_VERSION + "_" + arch.substr(0, arch.find('\n')) + ".deb";
  return {
      {"radfarm",
       (out / ("radfarm" + suffix)).string(),
       {"radfarm"},
       {"/usr/share/doc/radfarm/copyright", "/usr/share/doc/radfarm/changelog.Debian.gz",
        "/usr/share/doc/radfarm/USAGE.md", "/usr/share/doc/radfarm/examples/cornell-box.toml",
        "/usr/share/doc/radfarm/examples/cornell-box.obj",
        "/usr/share/doc/radfarm/examples/cornell-box.mtl", "/usr/share/lintian/overrides/radfarm",
        // The Blender add-on, which `radfarm blender-addon install` copies from here.
        "/usr/share/radfarm/blender/radfarm_bake/__init__.py",
        "/usr/share/radfarm/blender/radfarm_bake/apply.py",
        "/usr/share/radfarm/blender/radfarm_bake/export.py",
        "/usr/share/radfarm/blender/radfarm_bake/job_runner.py",
        "/usr/share/radfarm/blender/radfarm_bake/lit_glb.py",
        "/usr/share/radfarm/blender/radfarm_bake/operators.py",
        "/usr/share/radfarm/blender/radfarm_bake/panel.py",
        "/usr/share/radfarm/blender/radfarm_bake/settings.py",
        "/usr/share/radfarm/blender/radfarm_bake/viewport.py"},
       "",
       ""},
      {"radfarm-master",
       (out / ("radfarm-master" + suffix)).string(),
       {"radfarmd"},
       {"/usr/lib/systemd/system/radfarmd.service", "/etc/radfarm/radfarmd.conf",
        "/usr/share/doc/radfarm-master/OPERATIONS.md", "/usr/share/doc/radfarm-master/CONTROL.md",
        "/usr/share/doc/radfarm-master/copyright",
        "/usr/share/doc/radfarm-master/changelog.Debian.gz",
        "/usr/share/lintian/overrides/radfarm-master"},
       "radfarm",
       "/var/lib/radfarm"},
      {"radfarm-agent",
       (out / ("radfarm-agent" + suffix)).string(),
       {"radfarm-agent"},
       {"/usr/lib/systemd/system/radfarm-agent.service", "/etc/radfarm/agent.conf",
        "/usr/share/doc/radfarm-agent/OPERATIONS.md",
        "/usr/share/doc/radfarm-agent/examples/radfarm-agent.htcondor.sub",
        "/usr/share/doc/radfarm-agent/examples/radfarm-agent.slurm.sh",
        "/usr/share/doc/radfarm-agent/copyright",
        "/usr/share/doc/radfarm-agent/changelog.Debian.gz",
        "/usr/share/lintian/overrides/radfarm-agent"},
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
    if (!built.count(binary)) continue;
    expected.insert("/usr/bin/" + binary);
    expected.insert("/usr/share/man/man1/" + binary + ".1.gz");  // help2man, at build time
  }
  EXPECT_EQ(Contents(package.deb), expected)
      << "dpkg-deb -c " << package.deb << " (no manual pages: was help2man installed at cmake?)";
}

void ExpectControlFields(const Package& package) {
  const auto field = [&](const std::string& name) {
    std::string value = RunCommand("dpkg-deb -f " + Quote(package.deb) + " " + name).output;
    while (!value.empty() && value.back() == '\n') value.pop_back();
    return value;
  };
  EXPECT_EQ(field("Package"), package.name);
  EXPECT_EQ(field("Version"), RADFARM_DEB_VERSION);
  EXPECT_EQ(field("Maintainer"), RADFARM_PACKAGE_MAINTAINER);
  const std::string depends = field("Depends");
  // The daemons' maintainer scripts make their system users.
  if (!package.user.empty()) {
    EXPECT_NE(depends.find("adduser"), std::string::npos) << depends;
  }
  // dpkg-shlibdeps found the libraries the binaries link.
  if (HoldsABinary(package)) {
    EXPECT_NE(depends.find("libc6"), std::string::npos) << depends;
  }
}

void ExpectConfigsAreConffiles(const Package& package) {
  std::string expected;
  for (const std::string& file : package.files) {
    if (file.rfind("/etc/", 0) == 0) expected += file + "\n";
  }
  const testing::CommandResult conffiles =
      RunCommand("dpkg-deb -I " + Quote(package.deb) + " conffiles");
  if (expected.empty()) {
    EXPECT_NE(conffiles.exit_code, 0) << "a conffiles list in " << package.deb;
    return;
  }
  ASSERT_EQ(conffiles.exit_code, 0) << conffiles.output;
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
    for (const char* forbidden :
         {"systemctl start", "systemctl enable", "systemctl restart", "systemctl reload-or-restart",
          "--now", "deb-systemd-invoke start", "deb-systemd-invoke restart",
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

// `radfarm render` shipped only in radfarm-master, so a single-machine user had to install the
// master. The CLI is its own package now, which the master depends on.
void ExpectTheCommandLineInAPackageOfItsOwn(const std::vector<Package>& packages) {
  if (PackagedBinaries().count("radfarm")) {
    EXPECT_EQ(Contents(packages[0].deb).count("/usr/bin/radfarm"), 1u) << packages[0].deb;
  }
  const auto depends = [](const Package& package) {
    return RunCommand("dpkg-deb -f " + Quote(package.deb) + " Depends").output;
  };
  const std::string master = depends(packages[1]);
  EXPECT_NE(master.find(std::string("radfarm (= ") + RADFARM_DEB_VERSION + ")"), std::string::npos)
      << master;
  // The CLI needs neither a system user nor a daemon's package.
  const std::string cli = depends(packages[0]);
  EXPECT_EQ(cli.find("adduser"), std::string::npos) << cli;
  EXPECT_EQ(cli.find("radfarm-"), std::string::npos) << cli;
}

// `man radfarm` documents the subcommands too (help2man gets each one's --help).
void ExpectTheManualPageDocumentsTheSubcommands(const Package& cli) {
  if (!PackagedBinaries().count("radfarm")) return;
  TempDir root;
  ASSERT_EQ(RunCommand("dpkg-deb -x " + Quote(cli.deb) + " " + Quote(root.path())).exit_code, 0);
  const testing::CommandResult page =
      RunCommand("gzip -dc " + Quote((root.path() / "usr/share/man/man1/radfarm.1.gz").string()));
  ASSERT_EQ(page.exit_code, 0) << page.output;
  for (const char* text : {".SH SUBCOMMANDS", ".SS radfarm render", ".SS radfarm submit",
                           "Usage: radfarm render [OPTIONS] SCENE"}) {
    EXPECT_NE(page.output.find(text), std::string::npos) << text;
  }
  EXPECT_EQ(page.output.find(RADFARM_BINARY_DIR), std::string::npos) << "the build path leaked";
}

// Relative paths with a folder in `page` ("docs/USAGE.md"): the repository's, meaningless to a user
// of the packages. Installed paths are absolute; bare names ("CONTROL.md") are fine.
std::vector<std::string> RepositoryPaths(std::string page) {
  page = std::regex_replace(page, std::regex(R"(\\-)"), "-");  // roff's "\-" is a hyphen
  // Folders in lower case, as the repository's are ("OUT/NAME.obj" is a placeholder).
  const std::regex path(
      R"([a-z0-9_.-]+(/[a-z0-9_.-]+)*/[A-Za-z0-9_.-]+\.(md|h|cc|toml|obj|mtl|gltf|glb|sh|sub))");
  std::vector<std::string> found;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), path); it != std::sregex_iterator();
       ++it) {
    const std::string before = it->prefix().str();
    if (!before.empty() && before.back() == '/') continue;  // an installed, absolute path
    found.push_back(it->str());
  }
  return found;
}

// A manual page was --help reformatted, pointing into the repository. Each has sections a user
// can live by (from packaging/man/PROGRAM.h2m) and names only installed files.
void ExpectManualPagesAUserCanLiveBy(const std::vector<Package>& packages) {
  const std::map<std::string, std::vector<std::string>> sections = {
      {"radfarm",
       {".SH \"SCENES AND JOB FILES\"", ".SH OUTPUTS", ".SH \"EXIT STATUS\"", ".SH ENVIRONMENT",
        ".SH FILES", "/usr/share/doc/radfarm/USAGE.md",
        "/usr/share/doc/radfarm/examples/cornell\\-box.toml"}},
      {"radfarmd", {".SH \"EXIT STATUS\"", ".SH FILES", ".SH EXAMPLES"}},
      {"radfarm-agent", {".SH \"IDLE POLICY\"", ".SH \"EXIT STATUS\"", ".SH FILES"}}};
  for (const Package& package : packages) {
    for (const std::string& binary : package.binaries) {
      if (!PackagedBinaries().count(binary)) continue;
      SCOPED_TRACE(binary);
      TempDir root;
      ASSERT_EQ(
          RunCommand("dpkg-deb -x " + Quote(package.deb) + " " + Quote(root.path())).exit_code, 0);
      const testing::CommandResult page = RunCommand(
          "gzip -dc " + Quote((root.path() / ("usr/share/man/man1/" + binary + ".1.gz")).string()));
      ASSERT_EQ(page.exit_code, 0) << page.output;
      for (const std::string& text : sections.at(binary)) {
        EXPECT_NE(page.output.find(text), std::string::npos) << text;
      }
      EXPECT_EQ(RepositoryPaths(page.output), std::vector<std::string>{});
    }
  }
}

// lintian reported 6 errors (no copyright file, no changelog, a maintainer at localhost) and
// no-manual-page for every program. Every error and warning is now fixed, or
// overridden in packaging/debian/PACKAGE/lintian-overrides with the reason beside it.
void ExpectLintianFindsNoErrorOrWarning(const std::vector<Package>& packages) {
  ASSERT_TRUE(HaveTool("lintian"))
      << "lintian is not installed (scripts/install-deps --tests installs it)";
  std::string debs;
  for (const Package& package : packages) debs += " " + Quote(package.deb);
  const testing::CommandResult lintian = RunCommand(
      "lintian --fail-on error,warning --display-level '>=warning' --no-tag-display-limit" + debs);
  EXPECT_EQ(lintian.exit_code, 0) << lintian.output;
  std::istringstream lines(lintian.output);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_TRUE(line.rfind("E: ", 0) != 0 && line.rfind("W: ", 0) != 0) << line;
  }
}

// One test: cpack runs once (it also runs the build's preinstall step, a no-op on a built tree;
// two at once in one build tree would race).
TEST(PackageTest, CpackBuildsThreePackagesThatLintianPasses) {
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

  const std::vector<Package> packages = Packages(out.path());
  for (const Package& package : packages) {
    SCOPED_TRACE(package.name);
    ExpectExactlyItsFiles(package);
    ExpectControlFields(package);
    ExpectConfigsAreConffiles(package);
    if (!package.user.empty()) ExpectScriptsCreateTheUserAndStartNothing(package);
  }
  ExpectTheCommandLineInAPackageOfItsOwn(packages);
  ExpectTheManualPageDocumentsTheSubcommands(packages[0]);
  ExpectManualPagesAUserCanLiveBy(packages);
  ExpectLintianFindsNoErrorOrWarning(packages);
}

// An override hides a finding, so each says why, in a comment line right above it.
TEST(LintianOverridesTest, EveryOverrideSaysWhy) {
  const std::filesystem::path debian =
      std::filesystem::path(RADFARM_SOURCE_DIR) / "packaging/debian";
  int overrides = 0;
  for (const auto& entry : std::filesystem::directory_iterator(debian)) {
    const std::filesystem::path file = entry.path() / "lintian-overrides";
    if (!std::filesystem::exists(file)) continue;
    std::istringstream lines(ReadFile(file));
    bool explained = false;
    for (std::string line; std::getline(lines, line);) {
      if (line.empty()) {
        explained = false;
      } else if (line[0] == '#') {
        explained = line.find_first_not_of("# ") != std::string::npos;
      } else {
        ++overrides;
        EXPECT_TRUE(explained) << file << ": no comment says why for '" << line << "'";
      }
    }
  }
  EXPECT_GT(overrides, 0) << "no overrides found under " << debian;
}

}  // namespace
}  // namespace radfarm::packaging
