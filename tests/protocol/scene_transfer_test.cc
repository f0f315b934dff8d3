#include "protocol/scene_transfer.h"

#include <gtest/gtest.h>

#include "base/result.h"
#include "protocol/frame_codec.h"

namespace radfarm::protocol {
namespace {

std::vector<uint8_t> Blob(size_t size) {
  std::vector<uint8_t> b(size);
  for (size_t i = 0; i < size; ++i) b[i] = static_cast<uint8_t>(i * 131 + (i >> 8));
  return b;
}

// Serves `blob` to `assembler` with up to `window` requests in flight, through the wire.
Status Fetch(const std::vector<uint8_t>& blob, SceneAssembler* assembler, int window) {
  std::vector<SceneRequestMsg> in_flight;
  while (!assembler->complete()) {
    while (static_cast<int>(in_flight.size()) < window) {
      std::optional<SceneRequestMsg> r = assembler->NextRequest();
      if (!r) break;
      in_flight.push_back(*r);
    }
    if (in_flight.empty()) return Error{"stalled"};
    Result<SceneChunkMsg> chunk = MakeSceneChunk(blob, in_flight.front());
    in_flight.erase(in_flight.begin());
    RADFARM_RETURN_IF_ERROR(chunk);
    Result<DecodedFrame> wire = DecodeFrame(EncodeFrame(*chunk));
    RADFARM_RETURN_IF_ERROR(wire);
    RADFARM_RETURN_IF_ERROR(assembler->Add(std::get<SceneChunkMsg>(wire->message)));
  }
  return Ok{};
}

TEST(ProtocolSceneTest, Sha256KnownAnswer) {
  const std::string abc = "abc";
  const SceneHash h = HashScene(std::span(reinterpret_cast<const uint8_t*>(abc.data()), 3));
  EXPECT_EQ(HashToHex(h), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  Result<SceneHash> parsed = HashFromHex(HashToHex(h));
  ASSERT_TRUE(parsed);
  EXPECT_EQ(*parsed, h);
  EXPECT_FALSE(HashFromHex("abc"));
  EXPECT_FALSE(HashFromHex(std::string(64, 'g')));
}

TEST(ProtocolSceneTest, ChunkedFetchReassemblesAndVerifies) {
  for (size_t size : {1u, 999u, 1000u, 1001u, 10000u}) {
    for (int window : {1, 3}) {
      const std::vector<uint8_t> blob = Blob(size);
      SceneAssembler assembler(HashScene(blob), 1 << 20, 1000);
      ASSERT_TRUE(Fetch(blob, &assembler, window)) << size;
      EXPECT_TRUE(assembler.complete());
      EXPECT_EQ(assembler.TakeBlob(), blob);
      EXPECT_FALSE(assembler.NextRequest());
    }
  }
}

TEST(ProtocolSceneTest, WrongContentFailsTheHashCheck) {
  const std::vector<uint8_t> blob = Blob(5000);
  std::vector<uint8_t> evil = blob;
  evil[4321] ^= 1;
  SceneAssembler assembler(HashScene(blob), 1 << 20, 1000);
  Status s = Fetch(evil, &assembler, 2);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("SHA-256"), std::string::npos) << s.error();
  EXPECT_FALSE(assembler.complete());
  EXPECT_TRUE(assembler.failed());
  EXPECT_TRUE(assembler.TakeBlob().empty());
}

TEST(ProtocolSceneTest, BadChunksAreRejected) {
  const std::vector<uint8_t> blob = Blob(3000);
  const SceneHash hash = HashScene(blob);
  const SceneChunkMsg first = *MakeSceneChunk(blob, {hash, 0, 1000});
  const SceneChunkMsg second = *MakeSceneChunk(blob, {hash, 1000, 1000});

  SceneAssembler gap(hash, 1 << 20, 1000);
  EXPECT_FALSE(gap.Add(second));  // out of order
  EXPECT_FALSE(gap.Add(first));   // and failed for good

  SceneAssembler other(hash);
  SceneChunkMsg foreign = first;
  foreign.scene_hash[0] ^= 1;
  EXPECT_FALSE(other.Add(foreign));

  SceneAssembler resized(hash);
  ASSERT_TRUE(resized.Add(first));
  SceneChunkMsg grown = second;
  grown.total_size = 4000;
  EXPECT_FALSE(resized.Add(grown));

  SceneAssembler small(hash, 2999);
  Status s = small.Add(first);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("exceeds the limit"), std::string::npos);
}

TEST(ProtocolSceneTest, MakeSceneChunkRejectsOffsetsPastTheEnd) {
  const std::vector<uint8_t> blob = Blob(10);
  EXPECT_FALSE(MakeSceneChunk(blob, {HashScene(blob), 10, 5}));
  Result<SceneChunkMsg> tail = MakeSceneChunk(blob, {HashScene(blob), 8, 5});
  ASSERT_TRUE(tail);
  EXPECT_EQ(tail->data.size(), 2u);
  EXPECT_EQ(tail->total_size, 10u);
}

}  // namespace
}  // namespace radfarm::protocol
