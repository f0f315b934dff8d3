// An agent that sends an invalid batch result (a patch id out of range) is disconnected and
// blocklisted, and the job still ends with render's bytes: a faulty or hostile agent cannot
// change a result. The liar is a hand-driven protocol client in this test.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>

#include "protocol/farm_secret.h"
#include "protocol/frame_decoder.h"
#include "protocol/protocol_session.h"
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

// A blocking agent speaking the protocol by hand: batches alone (version 5), no point work.
class HandAgent {
 public:
  HandAgent(const std::string& address, const protocol::FarmSecret& secret, std::string name)
      : session_(protocol::ProtocolSession::ForAgent(
            secret, {std::move(name), 1, protocol::kMinProtocolVersion, protocol::kPackedHitsVersion})) {
    const size_t colon = address.rfind(':');
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_port = htons(static_cast<uint16_t>(std::stoi(address.substr(colon + 1))));
    inet_pton(AF_INET, address.substr(0, colon).c_str(), &sa.sin_addr);
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    timeval timeout{60, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&sa), sizeof sa) == 0;
  }
  ~HandAgent() { ::close(fd_); }

  bool Handshake() {
    if (!connected_) return false;
    Result<std::vector<uint8_t>> hello = session_.Start();
    if (!hello || !Write(*hello)) return false;
    while (!session_.authenticated()) {
      std::optional<protocol::DecodedFrame> frame = Read();
      if (!frame) return false;
      Result<protocol::ProtocolSession::Accepted> a = session_.Accept(*frame);
      if (!a) return false;
      if (!a->reply.empty() && !Write(a->reply)) return false;
    }
    return true;
  }
  // The next application message, skipping heartbeats; nullopt once the master closed.
  std::optional<protocol::Message> NextMessage() {
    while (true) {
      std::optional<protocol::DecodedFrame> frame = Read();
      if (!frame) return std::nullopt;
      Result<protocol::ProtocolSession::Accepted> a = session_.Accept(*frame);
      if (!a) return std::nullopt;
      if (std::holds_alternative<protocol::HeartbeatMsg>(frame->message)) continue;
      if (std::holds_alternative<protocol::CloseMsg>(frame->message)) return frame->message;
      return frame->message;
    }
  }
  bool Send(const protocol::Message& message) {
    Result<std::vector<uint8_t>> frame = session_.Encode(message);
    return frame && Write(*frame);
  }

 private:
  bool Write(const std::vector<uint8_t>& bytes) {
    return ::write(fd_, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
  }
  std::optional<protocol::DecodedFrame> Read() {
    while (true) {
      Result<std::optional<std::vector<uint8_t>>> next = decoder_.NextBody();
      if (!next) return std::nullopt;
      if (*next) {
        Result<protocol::DecodedFrame> frame = session_.Decode(**next);
        if (!frame) return std::nullopt;
        return std::move(frame).value();
      }
      uint8_t buffer[65536];
      const ssize_t n = ::read(fd_, buffer, sizeof buffer);
      if (n <= 0) return std::nullopt;
      if (!decoder_.Feed(std::span(buffer, size_t(n)))) return std::nullopt;
    }
  }

  protocol::ProtocolSession session_;
  protocol::FrameDecoder decoder_;
  int fd_ = -1;
  bool connected_ = false;
};

TEST_F(FarmTest, AnAgentSendingInvalidResultsIsBlocklistedForTheJobAfterThree) {
  StartMaster();
  std::ifstream in(farm_.secret_file());
  std::string hex;
  in >> hex;
  Result<protocol::FarmSecret> secret = protocol::FarmSecret::FromHex(hex);
  ASSERT_TRUE(secret.ok());
  const int64_t id = Submit("cornell-box.toml", kShortJob);

  HandAgent liar(master_address(), *secret, "liar");
  ASSERT_TRUE(liar.Handshake()) << MasterLog();
  // Every lease it gets, it answers with a lie: every ray of the first batch "hits" a patch that
  // does not exist. The first two lies cost it only those leases; the third, the job.
  int lies = 0;
  std::optional<protocol::Message> message;
  while ((message = liar.NextMessage())) {
    if (const auto* close = std::get_if<protocol::CloseMsg>(&*message)) {
      EXPECT_EQ(close->code, protocol::CloseCode::kBlocklisted) << close->detail;
      EXPECT_NE(close->detail.find("job " + std::to_string(id) + ": 3 results failed validation"),
                std::string::npos)
          << close->detail;
      break;
    }
    const auto* lease = std::get_if<protocol::LeaseAssignmentMsg>(&*message);
    if (lease == nullptr) continue;
    protocol::BatchOutcome lie;
    lie.lease = {lease->job_id, lease->batches[0].batch_id, lease->batches[0].attempt_id};
    lie.hits = {{lease->patch_count + 7, lease->batches[0].ray_count}};
    ASSERT_TRUE(liar.Send(protocol::LeaseResultMsg{{lie}}));
    ++lies;
  }
  EXPECT_EQ(lies, 3) << MasterLog();
  const std::string log = MasterLog();
  EXPECT_EQ(CountLines(log, "result rejected (invalid, 1 of 3)"), 1u) << log;
  EXPECT_EQ(CountLines(log, "result rejected (invalid, 3 of 3)"), 1u) << log;
  EXPECT_EQ(CountLines(log, "agent liar blocklisted for job " + std::to_string(id)), 1u) << log;

  // Coming back under the same name is let in (it may work for other jobs), but gets no lease of
  // this one: an honest agent finishes the job with render's bytes.
  HandAgent again(master_address(), *secret, "liar");
  ASSERT_TRUE(again.Handshake());
  StartAgent("honest");
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
  EXPECT_EQ(CountLines(MasterLog(), "refused"), 0u) << MasterLog();
  // The job's log says who was blocklisted and why.
  const CommandResult events = Cli({"log", std::to_string(id)});
  EXPECT_NE(events.out.find("agent liar is blocklisted for this job"), std::string::npos)
      << events.out;
}

}  // namespace
}  // namespace radfarm::testing
