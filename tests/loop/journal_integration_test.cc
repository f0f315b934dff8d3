// The log's priorities in a real journal: systemd-cat connects log_probe's stderr to journald and
// `journalctl -p warning` must then show the probe's warning and error lines and nothing else.
// Needs a running systemd-journald; a machine without one (a container with another init) skips.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <string>

#include "testing/child_process.h"

namespace radfarm::loop {
namespace {

using testing::RunCommand;

constexpr const char* kJournalStdout = "/run/systemd/journal/stdout";

std::string Journal(const std::string& tag, const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"/usr/bin/journalctl", "--no-pager", "-o", "cat", "-t", tag};
  args.insert(args.end(), extra.begin(), extra.end());
  return RunCommand(args).out;
}

TEST(JournalIntegrationTest, JournalctlPriorityWarningShowsWarningsAndErrorsOnly) {
  if (!std::filesystem::exists(kJournalStdout)) {
    GTEST_SKIP() << "no systemd-journald runs on this machine (" << kJournalStdout
                 << " is missing), so there is no journal to log into";
  }
  const std::string tag = "radfarm-log-probe-" + std::to_string(::getpid()) + "-" +
                          std::to_string(std::random_device{}());
  // systemd-cat connects stdout and stderr to the journal's stream; $JOURNAL_STREAM is set from
  // that stream as systemd sets it for a service, whether or not this systemd-cat sets it itself.
  const auto cat =
      RunCommand({"/usr/bin/systemd-cat", "-t", tag, "/bin/sh", "-c",
                  "JOURNAL_STREAM=$(stat -L -c %d:%i /proc/self/fd/2) exec \"$0\" \"$1\"",
                  RADFARM_LOG_PROBE_PATH, tag});
  ASSERT_EQ(cat.exit_code, 0) << cat.err;
  // journald stores the lines asynchronously: wait until the last one is there.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  std::string all;
  while ((all = Journal(tag, {})).find(tag + " error") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "journal of " << tag << ":\n" << all;
    RunCommand({"/usr/bin/journalctl", "--sync"});
  }
  EXPECT_NE(all.find(tag + " info"), std::string::npos) << all;
  EXPECT_EQ(all.find("<6>"), std::string::npos) << "journald kept the prefix:\n" << all;
  const std::string warnings = Journal(tag, {"-p", "warning"});
  EXPECT_NE(warnings.find(tag + " warning"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find(tag + " error"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find(tag + " info"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find(tag + " debug"), std::string::npos) << warnings;
}

}  // namespace
}  // namespace radfarm::loop
