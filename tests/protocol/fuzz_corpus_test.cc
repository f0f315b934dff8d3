// Replays the committed fuzz seed corpus (tests/protocol/fuzz_corpus) through the decoder in the
// normal build, so every build exercises it, and checks it still holds a valid frame of every
// message type (regenerate with protocol_corpus_writer after a schema change).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "base/result.h"
#include "protocol/frame_codec.h"
#include "protocol/frame_decoder.h"

namespace radfarm::protocol {
namespace {

const std::filesystem::path kCorpus =
    std::filesystem::path(RADFARM_SOURCE_DIR) / "tests/protocol/fuzz_corpus";

std::vector<uint8_t> ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Decodes a stream fed one byte at a time; the frames, or the error that stopped it.
Result<std::vector<Message>> DecodeBytewise(const std::vector<uint8_t>& bytes) {
  FrameDecoder decoder;
  std::vector<Message> out;
  for (uint8_t b : bytes) {
    RADFARM_RETURN_IF_ERROR(decoder.Feed(std::span(&b, 1)));
    for (;;) {
      Result<std::optional<DecodedFrame>> next = decoder.Next();
      RADFARM_RETURN_IF_ERROR(next);
      if (!*next) break;
      out.push_back(std::move((*next)->message));
    }
  }
  if (decoder.buffered_bytes() != 0) return Error{"trailing bytes"};
  return out;
}

TEST(ProtocolCorpusTest, EveryCorpusFileDecodes) {
  ASSERT_TRUE(std::filesystem::is_directory(kCorpus)) << kCorpus;
  std::set<std::string> types;
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kCorpus)) {
    const std::vector<uint8_t> bytes = ReadFile(entry.path());
    ++files;
    Result<std::vector<Message>> messages = DecodeBytewise(bytes);
    ASSERT_TRUE(messages) << entry.path() << ": " << messages.error();
    if (entry.path().extension() == ".frame") {
      Result<DecodedFrame> frame = DecodeFrame(bytes);
      ASSERT_TRUE(frame) << entry.path() << ": " << frame.error();
      types.insert(std::string(MessageName(frame->message)));
    }
  }
  EXPECT_GE(files, std::variant_size_v<Message> + 2);
  EXPECT_EQ(types.size(), std::variant_size_v<Message>) << "regenerate the corpus";
}

}  // namespace
}  // namespace radfarm::protocol
