#include "protocol/scene_transfer.h"

#include <gtest/gtest.h>

#include "base/result.h"
#include "protocol/frame_codec.h"

namespace radfarm::protocol {
namespace {

// Bytes zstd cannot shrink (xorshift), so the compressed scene takes as many chunks as the blob.
std::vector<uint8_t> Blob(size_t size) {
  std::vector<uint8_t> b(size);
  uint64_t x = 88172645463325252ull;
  for (size_t i = 0; i < size; ++i) {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    b[i] = static_cast<uint8_t>(x);
  }
  return b;
}

// Serves `scene` to `assembler` with up to `window` requests in flight, through the wire, then
// unpacks what came (as the agent does on its work queue).
Result<std::vector<uint8_t>> Fetch(const PackedScene& scene, SceneAssembler* assembler,
                                   int window) {
  std::vector<SceneRequestMsg> in_flight;
  while (!assembler->complete()) {
    while (static_cast<int>(in_flight.size()) < window) {
      std::optional<SceneRequestMsg> r = assembler->NextRequest();
      if (!r) break;
      in_flight.push_back(*r);
    }
    if (in_flight.empty()) return Error{"stalled"};
    Result<SceneChunkMsg> chunk = MakeSceneChunk(scene, in_flight.front());
    in_flight.erase(in_flight.begin());
    RADFARM_RETURN_IF_ERROR(chunk);
    Result<DecodedFrame> wire = DecodeFrame(EncodeFrame(*chunk));
    RADFARM_RETURN_IF_ERROR(wire);
    RADFARM_RETURN_IF_ERROR(assembler->Add(std::get<SceneChunkMsg>(wire->message)));
  }
  return UnpackReceived(assembler->TakeReceived());
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
      const PackedScene packed = PackScene(blob);
      EXPECT_EQ(packed.hash, HashScene(blob));
      EXPECT_EQ(packed.size, size);
      SceneAssembler assembler(HashScene(blob), 1 << 20, 1000);
      Result<std::vector<uint8_t>> fetched = Fetch(packed, &assembler, window);
      ASSERT_TRUE(fetched) << size << ": " << fetched.error();
      EXPECT_TRUE(assembler.complete());
      EXPECT_EQ(assembler.received_bytes(), packed.compressed.size());
      EXPECT_EQ(*fetched, blob);
      EXPECT_FALSE(assembler.NextRequest());
      EXPECT_TRUE(assembler.TakeReceived().compressed.empty());  // taken once
    }
  }
}

TEST(ProtocolSceneTest, WrongContentFailsTheHashCheck) {
  const std::vector<uint8_t> blob = Blob(5000);
  std::vector<uint8_t> evil = blob;
  evil[4321] ^= 1;
  SceneAssembler assembler(HashScene(blob), 1 << 20, 1000);
  Result<std::vector<uint8_t>> s = Fetch(PackScene(evil), &assembler, 2);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("SHA-256"), std::string::npos) << s.error();
  EXPECT_NE(s.error().find(HashToHex(HashScene(blob)).substr(0, 16)), std::string::npos)
      << s.error();
  // Every byte came as asked: the transfer is complete, its content is what failed.
  EXPECT_TRUE(assembler.complete());
  EXPECT_FALSE(assembler.failed());
}

TEST(ProtocolSceneTest, BadChunksAreRejected) {
  const std::vector<uint8_t> blob = Blob(3000);
  const PackedScene packed = PackScene(blob);
  const SceneHash hash = packed.hash;
  const SceneChunkMsg first = *MakeSceneChunk(packed, {hash, 0, 1000});
  const SceneChunkMsg second = *MakeSceneChunk(packed, {hash, 1000, 1000});

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

  SceneAssembler redeclared(hash);
  ASSERT_TRUE(redeclared.Add(first));
  SceneChunkMsg bigger = second;
  bigger.scene_size += 1;
  EXPECT_FALSE(redeclared.Add(bigger));

  SceneAssembler small(hash, 2999);
  Status s = small.Add(first);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("exceeds the limit"), std::string::npos);
}

// A malicious master declares a small scene and sends a frame that expands far beyond it (a
// "zip bomb"): the agent refuses it from the frame's header, before allocating the expansion.
TEST(ProtocolSceneTest, AFrameExpandingBeyondItsDeclaredSizeIsRefused) {
  const std::vector<uint8_t> zeros(64 << 20, 0);
  PackedScene bomb = PackScene(zeros);
  ASSERT_LT(bomb.compressed.size(), 10000u);  // 64 MiB in a few KB
  bomb.size = 1000;                           // what the chunks declare
  SceneAssembler assembler(bomb.hash, 1 << 20);
  Result<std::vector<uint8_t>> s = Fetch(bomb, &assembler, 1);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("zstd frame holds 67108864 bytes, the chunks declared 1000"),
            std::string::npos)
      << s.error();
  EXPECT_TRUE(assembler.complete());  // the chunks were in order; the unpacking refused them
  // Declared as it is, it is over the agent's limit, refused at the first chunk.
  bomb.size = zeros.size();
  SceneAssembler limited(bomb.hash, 1 << 20);
  s = Fetch(bomb, &limited, 1);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("size 67108864 ("), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("exceeds the limit of 1048576 bytes"), std::string::npos) << s.error();
  EXPECT_TRUE(limited.failed());
}

TEST(ProtocolSceneTest, MakeSceneChunkRejectsOffsetsPastTheEnd) {
  const PackedScene packed = PackScene(Blob(10));
  const uint64_t end = packed.compressed.size();
  EXPECT_FALSE(MakeSceneChunk(packed, {packed.hash, end, 5}));
  Result<SceneChunkMsg> tail = MakeSceneChunk(packed, {packed.hash, end - 2, 5});
  ASSERT_TRUE(tail);
  EXPECT_EQ(tail->data.size(), 2u);
  EXPECT_EQ(tail->total_size, end);
  EXPECT_EQ(tail->scene_size, 10u);
}

}  // namespace
}  // namespace radfarm::protocol
