// Writes the fuzzer's seed corpus: one valid frame of every message type, a LeaseResult also in
// version 4's form, a direct-light start's lease and result, a whole handshake as one stream, and
// every sample back to back. Run it after changing the schema or the samples:
//   build/tests/protocol/protocol_corpus_writer tests/protocol/fuzz_corpus
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "protocol/frame_codec.h"
#include "protocol/protocol_session.h"
#include "tests/protocol/sample_messages.h"

namespace {

using namespace radfarm::protocol;

bool Write(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

std::string Lower(std::string_view s) {
  std::string out;
  for (char c : s) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// The agent's half of a handshake (Hello, Proof), as the master reads it. What follows is sealed
// (protocol/frame_seal.h): the fuzzer feeds whole inputs to ProtocolSession::Decode for that.
std::vector<uint8_t> HandshakeStream() {
  const FarmSecret secret = *FarmSecret::FromBytes(std::vector<uint8_t>(32, 7));
  ProtocolSession master = ProtocolSession::ForMaster(secret, MasterConfig{});
  ProtocolSession agent = ProtocolSession::ForAgent(secret, AgentConfig{"fuzz", 1});
  std::vector<uint8_t> stream = *agent.Start();
  auto challenge = master.Accept(*DecodeFrame(stream));
  auto proof = agent.Accept(*DecodeFrame(challenge->reply));
  auto welcome = master.Accept(*DecodeFrame(proof->reply));
  (void)agent.Accept(*DecodeFrame(welcome->reply));
  stream.insert(stream.end(), proof->reply.begin(), proof->reply.end());
  return stream;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  std::vector<uint8_t> all;
  int index = 1;
  for (const Message& message : testing::SampleMessages()) {
    const std::vector<uint8_t> frame = EncodeFrame(message);
    char name[64];
    std::snprintf(name, sizeof(name), "%02d_%s.frame", index++,
                  Lower(MessageName(message)).c_str());
    if (!Write(dir / name, frame)) return 1;
    all.insert(all.end(), frame.begin(), frame.end());
  }
  // The version-4 form of a LeaseResult (hits as structs), which this master still reads.
  for (const Message& message : testing::SampleMessages()) {
    if (!std::holds_alternative<LeaseResultMsg>(message)) continue;
    char name[64];
    std::snprintf(name, sizeof(name), "%02d_leaseresult_version4.frame", index);
    if (!Write(dir / name, EncodeFrame(message, 4))) return 1;
  }
  // A direct-light start's lease and result (version 7).
  for (const Message& message : testing::StartSamples()) {
    char name[64];
    std::snprintf(name, sizeof(name), "start_%s.frame", Lower(MessageName(message)).c_str());
    if (!Write(dir / name, EncodeFrame(message))) return 1;
  }
  // A refinement step's light scores' lease and result (version 8).
  for (const Message& message : testing::ScoreSamples()) {
    char name[64];
    std::snprintf(name, sizeof(name), "score_%s.frame", Lower(MessageName(message)).c_str());
    if (!Write(dir / name, EncodeFrame(message))) return 1;
  }
  if (!Write(dir / "all_messages.stream", all)) return 1;
  if (!Write(dir / "handshake.stream", HandshakeStream())) return 1;
  return 0;
}
