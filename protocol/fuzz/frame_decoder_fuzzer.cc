// libFuzzer target: arbitrary bytes through the incremental frame decoder, cut into chunks at
// places the input itself picks, and every decoded frame through a master and an agent session.
// Nothing may crash, leak or read out of bounds; every frame that decodes must re-encode to a
// frame that decodes to the same message.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "protocol/frame_codec.h"
#include "protocol/frame_decoder.h"
#include "protocol/protocol_session.h"

namespace {

using radfarm::protocol::DecodedFrame;

void CheckReencodes(const DecodedFrame& frame) {
  const std::vector<uint8_t> again = radfarm::protocol::EncodeFrame(frame.message, frame.version);
  auto decoded = radfarm::protocol::DecodeFrame(again);
  if (!decoded || !(decoded->message == frame.message)) std::abort();
}

void Authenticate(radfarm::protocol::ProtocolSession& master,
                  radfarm::protocol::ProtocolSession& agent) {
  using radfarm::protocol::DecodeFrame;
  auto challenge = master.Accept(*DecodeFrame(*agent.Start()));
  auto proof = agent.Accept(*DecodeFrame(challenge->reply));
  auto welcome = master.Accept(*DecodeFrame(proof->reply));
  (void)agent.Accept(*DecodeFrame(welcome->reply));
  if (!master.authenticated() || !agent.authenticated()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::protocol;
  static const FarmSecret secret = *FarmSecret::FromBytes(std::vector<uint8_t>(32, 7));
  // Small limit so the fuzzer also explores the oversized-frame path.
  FrameDecoder decoder(1u << 16);
  // Fresh sessions see the fuzzed frames as handshake input; an authenticated pair (a real
  // handshake first) sees them as steady-state traffic.
  ProtocolSession master = ProtocolSession::ForMaster(secret, MasterConfig{});
  ProtocolSession agent = ProtocolSession::ForAgent(secret, AgentConfig{"fuzz", 1});
  (void)agent.Start();
  ProtocolSession authed_master = ProtocolSession::ForMaster(secret, MasterConfig{});
  ProtocolSession authed_agent = ProtocolSession::ForAgent(secret, AgentConfig{"fuzz", 1});
  Authenticate(authed_master, authed_agent);
  std::span<const uint8_t> rest(data, size);
  // The first byte picks the chunk size, so frames split across every kind of boundary.
  const size_t chunk = size > 0 ? 1 + data[0] % 64 : 1;
  while (!rest.empty()) {
    const size_t n = std::min(chunk, rest.size());
    if (!decoder.Feed(rest.first(n))) break;
    rest = rest.subspan(n);
    for (;;) {
      auto next = decoder.Next();
      if (!next || !*next) break;
      CheckReencodes(**next);
      (void)master.Accept(**next);
      (void)agent.Accept(**next);
      (void)authed_master.Accept(**next);
      (void)authed_agent.Accept(**next);
    }
  }
  // The whole input as one frame, too.
  if (auto frame = DecodeFrame(std::span<const uint8_t>(data, size), 1u << 16)) {
    CheckReencodes(*frame);
  }
  // And as a sealed frame's body after a real handshake: without the session key nothing may
  // open (a forged Poly1305 tag is a 2^-106 chance, so success means the check was skipped).
  ProtocolSession sealed_master = ProtocolSession::ForMaster(secret, MasterConfig{});
  ProtocolSession sealed_agent = ProtocolSession::ForAgent(secret, AgentConfig{"fuzz", 1});
  Authenticate(sealed_master, sealed_agent);
  if (sealed_master.Decode(std::span<const uint8_t>(data, size))) std::abort();
  return 0;
}
