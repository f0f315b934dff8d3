// Priorities for journald: "<N>" prefixes exactly when stderr is the stream $JOURNAL_STREAM names.
// The journal is faked by a file whose device and inode $JOURNAL_STREAM names.
#include "loop/journal_stream.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "loop/log.h"

namespace radfarm::loop {
namespace {

std::string DeviceInode(int fd) {
  struct stat st {};
  EXPECT_EQ(::fstat(fd, &st), 0);
  return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
}

class TempFile {
 public:
  TempFile() {
    char name[] = "/tmp/radfarm-journal-XXXXXX";
    fd_ = ::mkstemp(name);
    path_ = name;
  }
  ~TempFile() {
    ::close(fd_);
    ::unlink(path_.c_str());
  }
  int fd() const { return fd_; }
  std::string Read() const {
    std::ifstream in(path_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

 private:
  int fd_ = -1;
  std::string path_;
};

TEST(JournalStreamTest, MatchesOnlyTheDescriptorsDeviceAndInode) {
  TempFile file, other;
  EXPECT_TRUE(FdIsJournalStream(file.fd(), DeviceInode(file.fd()).c_str()));
  EXPECT_FALSE(FdIsJournalStream(file.fd(), DeviceInode(other.fd()).c_str()));
  EXPECT_FALSE(FdIsJournalStream(file.fd(), nullptr));
}

TEST(JournalStreamTest, AMalformedValueMatchesNothing) {
  TempFile file;
  const std::string good = DeviceInode(file.fd());
  for (const std::string& bad : {std::string(""), std::string(":"), good.substr(0, good.find(':')),
                                 ":" + good.substr(good.find(':') + 1), good + ":7", good + "x",
                                 " " + good, std::string("-1:-1")}) {
    EXPECT_FALSE(FdIsJournalStream(file.fd(), bad.c_str())) << "'" << bad << "'";
  }
}

TEST(JournalStreamTest, AClosedDescriptorIsNoJournal) {
  EXPECT_FALSE(FdIsJournalStream(-1, "1:2"));
}

// stderr pointed at a file for the test's length, $JOURNAL_STREAM set as the test says.
class LogPrefixTest : public ::testing::Test {
 protected:
  void SetUp() override {
    saved_stderr_ = ::dup(STDERR_FILENO);
    ASSERT_GE(saved_stderr_, 0);
    ASSERT_EQ(::dup2(file_.fd(), STDERR_FILENO), STDERR_FILENO);
    SetMinLogLevel(LogLevel::kDebug);
  }
  void TearDown() override {
    ::dup2(saved_stderr_, STDERR_FILENO);
    ::close(saved_stderr_);
    ::unsetenv("JOURNAL_STREAM");
    DetectJournalStderr();
    SetMinLogLevel(LogLevel::kInfo);
  }
  void LogOneOfEach() {
    Log(LogLevel::kDebug, "probe", "a debug line");
    Log(LogLevel::kInfo, "probe", "an info line");
    Log(LogLevel::kWarning, "probe", "a warning line");
    Log(LogLevel::kError, "probe", "an error line");
  }
  std::vector<std::string> Lines() const {
    std::vector<std::string> lines;
    std::stringstream text(file_.Read());
    for (std::string line; std::getline(text, line);) lines.push_back(line);
    return lines;
  }

  TempFile file_;
  int saved_stderr_ = -1;
};

TEST_F(LogPrefixTest, EveryLineCarriesItsPriorityWhenStderrIsTheJournal) {
  ::setenv("JOURNAL_STREAM", DeviceInode(file_.fd()).c_str(), 1);
  DetectJournalStderr();
  LogOneOfEach();
  const std::vector<std::string> lines = Lines();
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_TRUE(lines[0].starts_with("<7>")) << lines[0];
  EXPECT_TRUE(lines[1].starts_with("<6>")) << lines[1];
  EXPECT_TRUE(lines[2].starts_with("<4>")) << lines[2];
  EXPECT_TRUE(lines[3].starts_with("<3>")) << lines[3];
  EXPECT_NE(lines[2].find("WARN  probe: a warning line"), std::string::npos) << lines[2];
}

// A child of a service inherits $JOURNAL_STREAM even when its stderr went to a file or terminal.
TEST_F(LogPrefixTest, NoPrefixWhenJournalStreamNamesAnotherFile) {
  TempFile elsewhere;
  ::setenv("JOURNAL_STREAM", DeviceInode(elsewhere.fd()).c_str(), 1);
  DetectJournalStderr();
  LogOneOfEach();
  const std::vector<std::string> lines = Lines();
  ASSERT_EQ(lines.size(), 4u);
  for (const std::string& line : lines) EXPECT_NE(line.front(), '<') << line;
}

TEST_F(LogPrefixTest, NoPrefixWithoutJournalStream) {
  ::unsetenv("JOURNAL_STREAM");
  DetectJournalStderr();
  LogOneOfEach();
  for (const std::string& line : Lines()) EXPECT_NE(line.front(), '<') << line;
}

TEST(SyslogPriorityTest, LevelsMapToSyslogPriorities) {
  EXPECT_EQ(SyslogPriority(LogLevel::kError), 3);
  EXPECT_EQ(SyslogPriority(LogLevel::kWarning), 4);
  EXPECT_EQ(SyslogPriority(LogLevel::kInfo), 6);
  EXPECT_EQ(SyslogPriority(LogLevel::kDebug), 7);
}

}  // namespace
}  // namespace radfarm::loop
