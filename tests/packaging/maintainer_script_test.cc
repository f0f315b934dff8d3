// The packages' maintainer scripts, run for real as dpkg would (postinst configure, again for an
// upgrade, postrm purge), inside a private mount namespace where /etc, /var/lib and /run/systemd
// are scratch copies: adduser really creates the system user, and the machine is left untouched.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "shell.h"

namespace radfarm::packaging {
namespace {

namespace fs = std::filesystem;
using testing::HaveTool;
using testing::Quote;
using testing::RunCommand;
using testing::TempDir;

struct Scripts {
  std::string package;
  std::string user;
  std::string state_dir;
};

// Run in the namespace as `sh run.sh SCRATCH SCRIPTS_DIR USER STATE_DIR`; prints what the test
// checks.
constexpr const char* kNamespaceScript = R"sh(set -e
scratch=$1 scripts=$2 user=$3 state=$4
mount --make-rprivate /
cp -a /etc "$scratch/etc"
mkdir "$scratch/var-lib"
mount --bind "$scratch/etc" /etc
mount --bind "$scratch/var-lib" /var/lib
# No systemd to talk to, even on a machine that runs one.
if [ -d /run/systemd ]; then mount -t tmpfs tmpfs /run/systemd; fi
sh "$scripts/postinst" configure
echo "passwd: $(getent passwd "$user")"
echo "state: $(stat -c '%U:%G %a' "$state")"
sh "$scripts/postinst" configure 0.1.0   # an upgrade: idempotent
echo "users: $(grep -c "^$user:" /etc/passwd)"
sh "$scripts/prerm" remove
sh "$scripts/postrm" remove
echo "after remove: $(test -d "$state" && echo kept)"
sh "$scripts/postrm" purge
echo "after purge: $(test -d "$state" && echo kept || echo gone)"
)sh";

TEST(MaintainerScriptTest, PostinstCreatesTheUserAndStateDirPurgeRemovesIt) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root (adduser, mount namespaces)";
  for (const char* tool : {"unshare", "adduser", "getent"}) {
    if (!HaveTool(tool)) GTEST_SKIP() << tool << " is not installed";
  }
  const testing::CommandResult probe = RunCommand("unshare --mount true");
  if (probe.exit_code != 0) {
    GTEST_SKIP() << "cannot make a mount namespace here: " << probe.output;
  }

  for (const Scripts& s : {Scripts{"radfarm-master", "radfarm", "/var/lib/radfarm"},
                           Scripts{"radfarm-agent", "radfarm-agent", "/var/lib/radfarm-agent"}}) {
    SCOPED_TRACE(s.package);
    TempDir scratch;
    ASSERT_FALSE(scratch.path().empty());
    const fs::path script = scratch.path() / "run.sh";
    std::ofstream(script) << kNamespaceScript;
    const std::string scripts = std::string(RADFARM_SOURCE_DIR) + "/packaging/debian/" + s.package;
    const testing::CommandResult run =
        RunCommand("unshare --mount sh " + Quote(script) + " " + Quote(scratch.path()) + " " +
                   Quote(scripts) + " " + s.user + " " + s.state_dir);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::string& out = run.output;
    EXPECT_NE(out.find("passwd: " + s.user + ":x:"), std::string::npos) << out;
    EXPECT_NE(out.find(":" + s.state_dir + ":/usr/sbin/nologin\n"), std::string::npos) << out;
    EXPECT_NE(out.find("state: " + s.user + ":" + s.user + " 750\n"), std::string::npos) << out;
    EXPECT_NE(out.find("users: 1\n"), std::string::npos) << out;
    EXPECT_NE(out.find("after remove: kept\n"), std::string::npos) << out;
    EXPECT_NE(out.find("after purge: gone\n"), std::string::npos) << out;
  }
}

}  // namespace
}  // namespace radfarm::packaging
