#include "loop/unix_listener.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <fstream>

#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::Bytes;
using testing::ExpectClosesClean;
using testing::RunUntil;
using testing::TempSocketPath;

bool Exists(const std::string& path) {
  struct stat st {};
  return lstat(path.c_str(), &st) == 0;
}

// Restores the umask when the test ends.
class ScopedUmask {
 public:
  explicit ScopedUmask(mode_t mask) : old_(umask(mask)) {}
  ~ScopedUmask() { umask(old_); }

 private:
  mode_t old_;
};

TEST(UnixListenerTest, SocketFileIsOwnerOnlyWhateverTheUmask) {
  ScopedUmask open_umask(0);  // bind alone would make the socket 0777
  EventLoop loop;
  const std::string path = TempSocketPath("mode");
  {
    Result<std::unique_ptr<UnixListener>> listener = UnixListener::Listen(loop, path, [](auto) {});
    ASSERT_TRUE(listener.ok()) << listener.error();
    struct stat st {};
    ASSERT_EQ(lstat(path.c_str(), &st), 0);
    EXPECT_TRUE(S_ISSOCK(st.st_mode));
    EXPECT_EQ(st.st_mode & 07777, 0600u);
    EXPECT_EQ(st.st_uid, geteuid());
  }
  EXPECT_FALSE(Exists(path));  // closing unlinks it
  ExpectClosesClean(loop);
}

TEST(UnixListenerTest, CarriesFramesAndNamesThePeerProcess) {
  EventLoop loop;
  const std::string path = TempSocketPath("echo");
  {
    std::vector<std::unique_ptr<FramedConnection>> accepted;
    Result<std::unique_ptr<UnixListener>> listener =
        UnixListener::Listen(loop, path, [&](std::unique_ptr<FramedConnection> c) {
          FramedConnection* raw = c.get();
          c->Start(
              {}, [raw](auto p) { EXPECT_TRUE(raw->Send(p).ok()); }, [](auto&) {});
          accepted.push_back(std::move(c));
        });
    ASSERT_TRUE(listener.ok()) << listener.error();
    std::vector<std::vector<uint8_t>> replies;
    Result<std::unique_ptr<FramedConnection>> client = FramedConnection::ConnectUnix(
        loop, path, {}, [&](auto p) { replies.emplace_back(p.begin(), p.end()); }, [](auto&) {});
    ASSERT_TRUE(client.ok()) << client.error();
    ASSERT_TRUE((*client)->Send(Bytes("status")).ok());
    ASSERT_TRUE(RunUntil(loop, [&] { return replies.size() == 1; }));
    EXPECT_EQ(replies[0], Bytes("status"));
    EXPECT_EQ((*client)->peer(), "unix:" + path);
    EXPECT_EQ(accepted.at(0)->peer(), "unix:" + path + " (pid " + std::to_string(getpid()) +
                                          " uid " + std::to_string(geteuid()) + ")");
  }
  ExpectClosesClean(loop);
}

TEST(UnixListenerTest, StaleSocketOfADeadDaemonIsReplaced) {
  EventLoop loop;
  const std::string path = TempSocketPath("stale");
  {
    // A socket file nobody listens on, as a crashed daemon leaves it.
    const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::strncpy(address.sun_path, path.c_str(), sizeof address.sun_path - 1);
    ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    close(fd);
    ASSERT_TRUE(Exists(path));
    Result<std::unique_ptr<UnixListener>> listener = UnixListener::Listen(loop, path, [](auto) {});
    ASSERT_TRUE(listener.ok()) << listener.error();
    testing::RawClient client;
    EXPECT_TRUE(client.ConnectUnix(path));
  }
  ExpectClosesClean(loop);
}

TEST(UnixListenerTest, LiveSocketIsLeftAlone) {
  EventLoop loop;
  const std::string path = TempSocketPath("live");
  {
    Result<std::unique_ptr<UnixListener>> first = UnixListener::Listen(loop, path, [](auto) {});
    ASSERT_TRUE(first.ok()) << first.error();
    Result<std::unique_ptr<UnixListener>> second = UnixListener::Listen(loop, path, [](auto) {});
    ASSERT_FALSE(second.ok());
    EXPECT_NE(second.error().find("another process is listening"), std::string::npos)
        << second.error();
    second = Error{""};  // the failed attempt must not unlink the live socket
    EXPECT_TRUE(Exists(path));
    testing::RawClient client;
    EXPECT_TRUE(client.ConnectUnix(path));
  }
  EXPECT_FALSE(Exists(path));
  ExpectClosesClean(loop);
}

TEST(UnixListenerTest, ARegularFileIsNotRemoved) {
  EventLoop loop;
  const std::string path = TempSocketPath("file");
  std::ofstream(path) << "precious";
  Result<std::unique_ptr<UnixListener>> listener = UnixListener::Listen(loop, path, [](auto) {});
  ASSERT_FALSE(listener.ok());
  EXPECT_NE(listener.error().find("not a socket"), std::string::npos) << listener.error();
  listener = Error{""};
  EXPECT_TRUE(Exists(path));
  unlink(path.c_str());
  ExpectClosesClean(loop);
}

TEST(UnixListenerTest, OverlongPathIsAnError) {
  EventLoop loop;
  Result<std::unique_ptr<UnixListener>> listener =
      UnixListener::Listen(loop, "/tmp/" + std::string(200, 'x'), [](auto) {});
  ASSERT_FALSE(listener.ok());
  EXPECT_NE(listener.error().find("the path must be 1 to 107 bytes"), std::string::npos)
      << listener.error();
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::loop
