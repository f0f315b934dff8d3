#include "loop/log.h"

#include <gtest/gtest.h>

#include <mutex>
#include <regex>
#include <thread>

namespace radfarm::loop {
namespace {

class LogTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SetLogSink([this](std::string_view line) { lines_.emplace_back(line); });
  }
  void TearDown() override {
    SetLogSink(nullptr);
    SetMinLogLevel(LogLevel::kInfo);
  }
  std::vector<std::string> lines_;  // the sink runs under the log mutex
};

TEST_F(LogTest, OneLineWithTimestampLevelAndComponent) {
  Log(LogLevel::kWarning, "scheduler", "lease 12 expired");
  ASSERT_EQ(lines_.size(), 1u);
  EXPECT_TRUE(std::regex_match(
      lines_[0],
      std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z WARN  scheduler: lease 12 expired)")))
      << lines_[0];
}

TEST_F(LogTest, StreamStyleWritesAtTheEndOfTheStatement) {
  LogLine(LogLevel::kError, "master") << "agent " << 7 << " lost";
  ASSERT_EQ(lines_.size(), 1u);
  EXPECT_NE(lines_[0].find("ERROR master: agent 7 lost"), std::string::npos) << lines_[0];
}

TEST_F(LogTest, LevelsBelowTheMinimumAreDropped) {
  Log(LogLevel::kDebug, "loop", "hidden");
  SetMinLogLevel(LogLevel::kDebug);
  Log(LogLevel::kDebug, "loop", "shown");
  SetMinLogLevel(LogLevel::kError);
  LogLine(LogLevel::kWarning, "loop") << "hidden too";
  ASSERT_EQ(lines_.size(), 1u);
  EXPECT_NE(lines_[0].find("DEBUG loop: shown"), std::string::npos);
}

// A peer-supplied string must not be able to start a line of its own.
TEST_F(LogTest, ControlCharactersAreEscaped) {
  Log(LogLevel::kInfo, "master", "agent 'evil\n2024-01-01T00:00:00.000Z ERROR fake: x'");
  ASSERT_EQ(lines_.size(), 1u);
  EXPECT_EQ(lines_[0].find('\n'), std::string::npos);
  EXPECT_NE(lines_[0].find("evil\\x0a2024"), std::string::npos) << lines_[0];
}

TEST_F(LogTest, LinesFromManyThreadsStayWhole) {
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([t] {
      for (int i = 0; i < 200; ++i)
        LogLine(LogLevel::kInfo, "worker") << "thread " << t << " line " << i;
    });
  }
  for (std::thread& thread : threads) thread.join();
  ASSERT_EQ(lines_.size(), 800u);
  for (const std::string& line : lines_) {
    EXPECT_TRUE(std::regex_search(line, std::regex(R"(INFO  worker: thread \d line \d+$)")))
        << line;
  }
}

}  // namespace
}  // namespace radfarm::loop
