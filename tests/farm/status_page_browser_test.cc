// The status page in a real browser: a farm on loopback (a master with --http and a web token, one
// agent), then tests/farm/status_page_browser.py drives headless Chromium through it (the job
// appears, its progress moves, pause and resume from the page, done, the agent listed) and saves
// the screenshot docs/OPERATIONS.md shows (written to the build directory, or to
// $RADFARM_SCREENSHOT). Chromium, chromedriver and python3-selenium come from
// scripts/install-deps --tests; without them this test fails, it does not skip.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

TEST_F(FarmTest, TheStatusPageFollowsAJobInARealBrowser) {
  const std::string token = "browser-token-0123456789abcdef";
  std::ofstream(Path("web.token")) << token << "\n";
  StartMaster({"--http", "127.0.0.1:0", "--http-token-file", Path("web.token")});
  StartAgent("desk-01");
  ASSERT_TRUE(farm_.WaitForAgents(1, std::chrono::seconds(60)));
  const std::string address = ReadFile(farm_.state_dir() + "/http.addr");
  ASSERT_FALSE(address.empty()) << MasterLog();

  const char* wanted = std::getenv("RADFARM_SCREENSHOT");
  const std::string screenshot =
      wanted ? wanted : std::string(RADFARM_BINARY_DIR "/status-page.png");
  const CommandResult r =
      RunCommand({"/usr/bin/python3", RADFARM_SOURCE_DIR "/tests/farm/status_page_browser.py",
                  "--url", "http://" + address.substr(0, address.find('\n')) + "/", "--token",
                  token, "--cli", RADFARM_CLI_PATH, "--control", control(), "--scene",
                  RADFARM_SOURCE_DIR "/scenes/cornell-box.toml", "--agent", "desk-01",
                  "--screenshot", screenshot});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err << "\nmaster:\n" << MasterLog();
  std::ifstream png(screenshot, std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << screenshot;
}

}  // namespace
}  // namespace radfarm::testing
