// The control socket against whatever bytes a client sends: paths and names
// that are not UTF-8, job ids beyond int64, a JSON frame announced at 1 GiB, an attachment that is
// announced and never sent, an idle client. Each is answered with an error or closed with a log
// line; radfarmd stays up and keeps serving.
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli/job_inputs.h"
#include "codec/job_bundle.h"
#include "tests/farm/farm_fixture.h"
#include "tests/farm/raw_peer.h"

namespace radfarm::testing {
namespace {

constexpr auto kControlAnswerTimeout = std::chrono::seconds(60);
// A master that computes every round itself: these jobs need no agent.
const std::vector<std::string> kMasterAlone = {"--local-round-rays", "100000000"};

// One request (and attachment) on a fresh connection; the answer's JSON, null if none came.
nlohmann::json ControlExchange(const std::string& control, const std::string& json,
                               const std::string& attachment = "") {
  const int fd = ConnectUnixSocket(control);
  if (fd < 0) return nullptr;
  (void)SendSome(fd, Frame(json) + (attachment.empty() ? "" : Frame(attachment)));
  const std::optional<std::string> answer = ReadFramePayload(fd, kControlAnswerTimeout);
  ::close(fd);
  if (!answer) return nullptr;
  return nlohmann::json::parse(*answer, nullptr, false);
}

void CopyFurnaceTo(const std::string& obj_path) {
  std::filesystem::copy_file(RADFARM_SOURCE_DIR "/scenes/furnace.mtl",
                             std::filesystem::path(obj_path).parent_path() / "furnace.mtl");
  std::filesystem::copy_file(RADFARM_SOURCE_DIR "/scenes/furnace.obj", obj_path);
}

// F1: `radfarm submit caf\xe9.obj` made radfarmd abort (nlohmann type_error.316) and kill every
// job.
TEST_F(FarmTest, ASceneWhosePathIsNotUtf8IsQueuedAndTheMasterStaysUp) {
  StartMaster(kMasterAlone);
  const std::string scene = Path("caf\xe9.obj");
  CopyFurnaceTo(scene);
  const CommandResult submitted = Cli({"submit", scene, "--rays", "200000", "--json"});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err << MasterLog();
  const nlohmann::json job = nlohmann::json::parse(submitted.out, nullptr, false);
  ASSERT_TRUE(job.is_object()) << submitted.out;
  // The bad byte is shown as U+FFFD; the job runs like any other.
  EXPECT_EQ(job["name"], "caf\xEF\xBF\xBD.obj");
  const CommandResult list = Cli({"list", "--json"});
  EXPECT_EQ(list.exit_code, 0) << list.err;
  ASSERT_TRUE(WaitForState(job["id"].get<int64_t>(), "done"));
  EXPECT_TRUE(master().running()) << MasterLog();
}

// F1: a fuzzed job bundle with 0xFF in a path did the same.
TEST_F(FarmTest, AJobBundleWithByte0xFFInItsPathIsAnsweredAndTheMasterStaysUp) {
  StartMaster(kMasterAlone);
  std::vector<std::string> warnings;
  Result<LoadedJob> loaded =
      LoadJobForSolve(RADFARM_SOURCE_DIR "/scenes/furnace.obj", {}, &warnings);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  loaded->job.scene_path = "/tmp/scene\xFF/furnace\xFF.obj";
  loaded->job.solver.max_rays = 200000;
  loaded->scene.materials[0].name = "glow\xFF";
  const std::vector<uint8_t> bundle = codec::EncodeJobBundle({loaded->job, loaded->scene});
  const std::string attachment(bundle.begin(), bundle.end());
  const nlohmann::json answer = ControlExchange(
      control(), R"({"command":"submit","attachment_bytes":)" + std::to_string(bundle.size()) + "}",
      attachment);
  ASSERT_TRUE(answer.is_object()) << MasterLog();
  ASSERT_EQ(answer["ok"], true) << answer;
  EXPECT_EQ(answer["job"]["name"], "furnace\xEF\xBF\xBD.obj");
  ASSERT_TRUE(WaitForState(answer["job"]["id"].get<int64_t>(), "done"));
  EXPECT_TRUE(master().running()) << MasterLog();
}

// F1: a non-UTF-8 --name made the CLI print a raw nlohmann exception.
TEST_F(FarmTest, ANameThatIsNotUtf8IsRefusedByTheCliNamingTheOption) {
  StartMaster(kMasterAlone);
  const CommandResult r = Cli(
      {"submit", RADFARM_SOURCE_DIR "/scenes/furnace.obj", "--name", "caf\xe9", "--rays", "1000"});
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--name: not UTF-8 text (byte 0xE9 at offset 3)"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
  // And a raw request whose JSON holds such a byte is refused as JSON, not fatal.
  const nlohmann::json answer = ControlExchange(control(), "{\"command\":\"list\",\"x\":\"\xff\"}");
  ASSERT_TRUE(answer.is_object()) << MasterLog();
  EXPECT_EQ(answer["code"], "bad_request") << answer;
  EXPECT_TRUE(master().running()) << MasterLog();
}

// F6: job id 18446744073709551615 was reported as "no job -1".
TEST_F(FarmTest, AJobIdBeyondInt64IsNotFoundByTheIdAsGiven) {
  StartMaster(kMasterAlone);
  nlohmann::json answer =
      ControlExchange(control(), R"({"command":"status","id":18446744073709551615})");
  ASSERT_TRUE(answer.is_object()) << MasterLog();
  EXPECT_EQ(answer["code"], "not_found");
  EXPECT_EQ(answer["error"], "no job 18446744073709551615");
  answer = ControlExchange(control(), R"({"command":"cancel","id":-3})");
  ASSERT_TRUE(answer.is_object()) << MasterLog();
  EXPECT_EQ(answer["code"], "bad_request");
  EXPECT_EQ(answer["error"], "'id' must not be negative");
  const CommandResult r = Cli({"status", "18446744073709551615"});
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("no job 18446744073709551615"), std::string::npos) << r.err;
}

// F6: the control socket buffered up to 1 GiB before applying its 1 MiB JSON limit. Now the
// prefix alone closes the connection: nothing of the announced gigabyte is ever sent here.
TEST_F(FarmTest, AJsonFrameAnnouncedAbove1MiBIsRefusedFromItsPrefix) {
  StartMaster(kMasterAlone);
  const int fd = ConnectUnixSocket(control());
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(SendSome(fd, FramePrefix(1u << 30)));
  EXPECT_TRUE(WaitForPeerClose(fd, kControlAnswerTimeout));
  ::close(fd);
  EXPECT_TRUE(WaitUntil([&] {
    return CountLines(MasterLog(), "exceeds the limit of 1048576 bytes; closed") > 0;
  })) << MasterLog();
  // An attachment longer than announced is refused from its prefix too.
  const int fd2 = ConnectUnixSocket(control());
  ASSERT_GE(fd2, 0);
  ASSERT_TRUE(SendSome(
      fd2, Frame(R"({"command":"submit","attachment_bytes":100})") + FramePrefix(1u << 29)));
  EXPECT_TRUE(WaitForPeerClose(fd2, kControlAnswerTimeout));
  ::close(fd2);
  EXPECT_TRUE(WaitUntil([&] {
    return CountLines(MasterLog(), "exceeds the limit of 100 bytes; closed") > 0;
  })) << MasterLog();
  EXPECT_EQ(Cli({"list"}).exit_code, 0);
}

// F6: a client that announced an attachment and never sent it was held open indefinitely; an idle
// client too.
TEST_F(FarmTest, AnAttachmentThatNeverComesAndAnIdleClientAreClosedAtTheDeadline) {
  StartMaster({"--local-round-rays", "100000000", "--control-timeout-ms", "300"});
  const int announcer = ConnectUnixSocket(control());
  const int idle = ConnectUnixSocket(control());
  ASSERT_GE(announcer, 0);
  ASSERT_GE(idle, 0);
  // The JSON, then the attachment's prefix and 10 of its 1000 bytes.
  ASSERT_TRUE(SendSome(announcer, Frame(R"({"command":"submit","attachment_bytes":1000})") +
                                      FramePrefix(1000) + std::string(10, 'x')));
  EXPECT_TRUE(WaitForPeerClose(announcer, kControlAnswerTimeout));
  EXPECT_TRUE(WaitForPeerClose(idle, kControlAnswerTimeout));
  ::close(announcer);
  ::close(idle);
  const std::string log = MasterLog();
  EXPECT_EQ(CountLines(log, "the announced attachment of 1000 bytes did not arrive within 300 ms"),
            1u)
      << log;
  EXPECT_EQ(CountLines(log, ": no request within 300 ms; closing"), 1u) << log;
  EXPECT_EQ(Cli({"list"}).exit_code, 0);
  EXPECT_TRUE(master().running()) << MasterLog();
}

}  // namespace
}  // namespace radfarm::testing
