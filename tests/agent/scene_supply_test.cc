#include "agent/scene_supply.h"

#include <gtest/gtest.h>

#include <deque>
#include <filesystem>
#include <optional>

#include "codec/patch_scene_codec.h"
#include "codec/point_context_blob.h"
#include "protocol/scene_transfer.h"
#include "tests/agent/agent_process.h"
#include "tests/agent/test_farm.h"
#include "tests/loop/loop_test_util.h"

namespace radfarm::agent {
namespace {

using loop::testing::RunUntil;
using testing::ReadTextFile;
using testing::ScratchDir;
using testing::WriteTextFile;

// A SceneSupply on a real loop and I/O queue, whose requests the test answers as a master would.
struct Harness {
  explicit Harness(std::optional<SceneStore> store) {
    io = loop::WorkQueue::Create(loop, 1, "test-io").value();
    SceneSupply::Callbacks callbacks;
    callbacks.on_ready = [this](const auto& scene) {
      ready.push_back(scene);
      if (at_ready) at_ready();
    };
    callbacks.on_context_ready = [this](const auto& context) { contexts.push_back(context); };
    callbacks.on_failed = [this](const auto&, auto reason, const std::string& why) {
      failures.emplace_back(reason, why);
    };
    callbacks.send_request = [this](const protocol::SceneRequestMsg& request) -> Status {
      requests.push_back(request);
      max_in_flight = std::max(max_in_flight, requests.size());
      return Ok{};
    };
    supply = std::make_unique<SceneSupply>(*io, std::move(store), "test-master", callbacks);
  }
  ~Harness() {
    io.reset();
    supply.reset();
    loop::testing::ExpectClosesClean(loop);
  }

  // Answers the requests in order, from `blob` packed as the master packs it, until none is left.
  void Serve(const std::vector<uint8_t>& blob) {
    const protocol::PackedScene packed = protocol::PackScene(blob);
    while (!requests.empty()) {
      const protocol::SceneRequestMsg request = requests.front();
      requests.pop_front();
      ++served;
      supply->OnChunk(protocol::MakeSceneChunk(packed, request).value());
    }
  }
  bool RunUntilSettled() {
    return RunUntil(loop,
                    [this] { return !ready.empty() || !contexts.empty() || !failures.empty(); });
  }

  loop::EventLoop loop;
  std::unique_ptr<loop::WorkQueue> io;
  std::unique_ptr<SceneSupply> supply;
  std::deque<protocol::SceneRequestMsg> requests;
  size_t max_in_flight = 0;
  int served = 0;
  std::vector<std::shared_ptr<const PreparedScene>> ready;
  std::vector<std::shared_ptr<const PreparedContext>> contexts;
  std::function<void()> at_ready;  // runs inside on_ready
  std::vector<std::pair<protocol::LeaseReturnReason, std::string>> failures;
};

TEST(SceneSupplyTest, FetchesWithPipelinedRequestsSavesAndKeepsTheScene) {
  ScratchDir dir;
  const PatchScene scene = testing::VariedBoxScene(testing::kBigBox);
  const std::vector<uint8_t> blob = codec::EncodePatchScene(scene);
  ASSERT_GT(protocol::PackScene(blob).compressed.size(), 2 * protocol::kMaxSceneChunkBytes)
      << "the compressed scene should take 3+ chunks";
  const protocol::SceneHash hash = protocol::HashScene(blob);
  Harness h(SceneStore::Open(dir.path()).value());

  ASSERT_TRUE(h.supply->Want(hash).ok());
  ASSERT_TRUE(RunUntil(h.loop, [&] { return !h.requests.empty(); }));  // nothing on disk
  EXPECT_EQ(h.requests.front().offset, 0u);
  EXPECT_EQ(h.requests.size(), 1u);        // the size is unknown until the first chunk
  ASSERT_TRUE(h.supply->Want(hash).ok());  // already under way: no second fetch
  EXPECT_EQ(h.requests.size(), 1u);
  h.Serve(blob);
  EXPECT_GT(h.max_in_flight, 1u);
  EXPECT_LE(h.max_in_flight, SceneSupply::kRequestWindow);
  ASSERT_TRUE(h.RunUntilSettled());
  ASSERT_TRUE(h.failures.empty()) << h.failures[0].second;
  ASSERT_EQ(h.ready.size(), 1u);
  EXPECT_EQ(h.ready[0]->hash, hash);
  EXPECT_EQ(h.ready[0]->patch_count(), scene.patches.size());
  EXPECT_EQ(h.supply->Find(hash), h.ready[0]);
  ASSERT_TRUE(RunUntil(h.loop, [&] { return h.supply->busy() == 0; }));  // the file committed
  SceneStore store = SceneStore::Open(dir.path()).value();
  EXPECT_EQ(store.Load(hash).blob, blob);
}

// The fetched scene is ready before its file is fsynced and renamed into place (the fsync of a
// big scene is not on the way to its first batch); the file follows, whole.
TEST(SceneSupplyTest, AFetchedSceneIsReadyBeforeItsFileIsInPlace) {
  ScratchDir dir;
  const std::vector<uint8_t> blob = codec::EncodePatchScene(testing::BoxScene(2));
  const protocol::SceneHash hash = protocol::HashScene(blob);
  const std::string path = SceneStore::Open(dir.path()).value().PathFor(hash);
  Harness h(SceneStore::Open(dir.path()).value());
  std::optional<bool> in_place_when_ready;
  h.at_ready = [&] { in_place_when_ready = std::filesystem::exists(path); };
  ASSERT_TRUE(h.supply->Want(hash).ok());
  ASSERT_TRUE(RunUntil(h.loop, [&] { return !h.requests.empty(); }));
  h.Serve(blob);
  ASSERT_TRUE(h.RunUntilSettled());
  ASSERT_TRUE(h.failures.empty()) << h.failures[0].second;
  ASSERT_TRUE(in_place_when_ready.has_value());
  EXPECT_FALSE(*in_place_when_ready);
  ASSERT_TRUE(RunUntil(h.loop, [&] { return h.supply->busy() == 0; }));
  EXPECT_EQ(SceneStore::Open(dir.path()).value().Load(hash).blob, blob);
  // Only the scene's file is left: its temporary was renamed, not copied.
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path() + "/scenes")) {
    EXPECT_EQ(entry.path().string(), path);
    ++files;
  }
  EXPECT_EQ(files, 1u);
}

TEST(SceneSupplyTest, AGoodFileIsUsedWithoutAFetch) {
  ScratchDir dir;
  const std::vector<uint8_t> blob = codec::EncodePatchScene(testing::BoxScene(2));
  const protocol::SceneHash hash = protocol::HashScene(blob);
  ASSERT_TRUE(SceneStore::Open(dir.path()).value().Save(hash, blob).ok());
  Harness h(SceneStore::Open(dir.path()).value());
  ASSERT_TRUE(h.supply->Want(hash).ok());
  ASSERT_TRUE(h.RunUntilSettled());
  EXPECT_EQ(h.ready.size(), 1u);
  EXPECT_TRUE(h.requests.empty());
}

TEST(SceneSupplyTest, ADamagedFileIsDeletedAndTheSceneFetchedAgain) {
  ScratchDir dir;
  const std::vector<uint8_t> blob = codec::EncodePatchScene(testing::BoxScene(2));
  const protocol::SceneHash hash = protocol::HashScene(blob);
  SceneStore store = SceneStore::Open(dir.path()).value();
  WriteTextFile(store.PathFor(hash), "garbage where the scene was");
  Harness h(SceneStore::Open(dir.path()).value());
  ASSERT_TRUE(h.supply->Want(hash).ok());
  ASSERT_TRUE(RunUntil(h.loop, [&] { return !h.requests.empty(); }));
  h.Serve(blob);
  ASSERT_TRUE(h.RunUntilSettled());
  EXPECT_EQ(h.ready.size(), 1u);
  EXPECT_GE(h.served, 1);
  ASSERT_TRUE(RunUntil(h.loop, [&] { return h.supply->busy() == 0; }));  // the file committed
  EXPECT_EQ(store.Load(hash).blob, blob);  // the file now holds the real scene
}

TEST(SceneSupplyTest, WithoutAStateDirectoryTheSceneIsFetchedAndKeptInMemory) {
  const std::vector<uint8_t> blob = codec::EncodePatchScene(testing::BoxScene(2));
  const protocol::SceneHash hash = protocol::HashScene(blob);
  Harness h(std::nullopt);
  ASSERT_TRUE(h.supply->Want(hash).ok());
  EXPECT_EQ(h.requests.size(), 1u);  // straight to the master
  h.Serve(blob);
  ASSERT_TRUE(h.RunUntilSettled());
  EXPECT_NE(h.supply->Find(hash), nullptr);
}

TEST(SceneSupplyTest, SceneUnavailableFailsTheScene) {
  const protocol::SceneHash hash = protocol::HashScene(std::vector<uint8_t>{1, 2, 3});
  Harness h(std::nullopt);
  ASSERT_TRUE(h.supply->Want(hash).ok());
  h.supply->OnUnavailable({hash});
  ASSERT_EQ(h.failures.size(), 1u);
  EXPECT_EQ(h.failures[0].first, protocol::LeaseReturnReason::kSceneUnavailable);
  // A later Want fetches anew: the master may have the scene by then.
  h.requests.clear();
  ASSERT_TRUE(h.supply->Want(hash).ok());
  EXPECT_EQ(h.requests.size(), 1u);
}

TEST(SceneSupplyTest, AnUndecodableSceneFailsAndIsNotFetchedAgain) {
  const std::vector<uint8_t> blob(5000, 0xab);  // verified by hash, but no PatchScene
  const protocol::SceneHash hash = protocol::HashScene(blob);
  Harness h(std::nullopt);
  ASSERT_TRUE(h.supply->Want(hash).ok());
  h.Serve(blob);
  ASSERT_TRUE(h.RunUntilSettled());
  ASSERT_EQ(h.failures.size(), 1u);
  EXPECT_EQ(h.failures[0].first, protocol::LeaseReturnReason::kFailed);
  EXPECT_NE(h.failures[0].second.find("cannot decode"), std::string::npos) << h.failures[0].second;
  EXPECT_FALSE(h.supply->Want(hash).ok());
  EXPECT_TRUE(h.requests.empty());
}

TEST(SceneSupplyTest, BytesThatAreNotTheSceneFailTheFetchOffTheLoopAndMayBeFetchedAgain) {
  const std::vector<uint8_t> blob =
      codec::EncodePatchScene(testing::VariedBoxScene(testing::kBigBox));
  const protocol::SceneHash hash = protocol::HashScene(blob);
  std::vector<uint8_t> tampered = blob;
  tampered[tampered.size() / 2] ^= 1;  // the same size, another SHA-256
  Harness h(std::nullopt);
  ASSERT_TRUE(h.supply->Want(hash).ok());
  // Served as the scene asked for: the chunks are in order, so the fetch completes and the
  // unpacking, on the I/O queue, finds the hash wrong.
  const protocol::PackedScene packed = protocol::PackScene(tampered);
  while (!h.requests.empty()) {
    protocol::SceneChunkMsg chunk = protocol::MakeSceneChunk(packed, h.requests.front()).value();
    h.requests.pop_front();
    chunk.scene_hash = hash;
    h.supply->OnChunk(chunk);
  }
  EXPECT_TRUE(h.failures.empty());  // not on the loop thread, inside OnChunk
  EXPECT_EQ(h.supply->busy(), 1u);
  ASSERT_TRUE(h.RunUntilSettled());
  ASSERT_EQ(h.failures.size(), 1u);
  EXPECT_EQ(h.failures[0].first, protocol::LeaseReturnReason::kFailed);
  EXPECT_NE(h.failures[0].second.find("SHA-256 of the decompressed bytes does not match"),
            std::string::npos)
      << h.failures[0].second;
  EXPECT_NE(h.failures[0].second.find("test-master"), std::string::npos) << h.failures[0].second;
  // A fault of that transfer, not of the scene: the next Want fetches it again.
  ASSERT_TRUE(h.supply->Want(hash).ok());
  h.Serve(blob);
  ASSERT_TRUE(RunUntil(h.loop, [&] { return !h.ready.empty(); }));
  EXPECT_EQ(h.failures.size(), 1u);
}

TEST(SceneSupplyTest, ABadChunkFailsTheFetchAndItsLateAnswersAreSkipped) {
  const std::vector<uint8_t> blob =
      codec::EncodePatchScene(testing::VariedBoxScene(testing::kBigBox));
  const protocol::PackedScene packed = protocol::PackScene(blob);
  const protocol::SceneHash hash = packed.hash;
  Harness h(std::nullopt);
  ASSERT_TRUE(h.supply->Want(hash).ok());
  // The first chunk claims another total size than the real one on the second.
  protocol::SceneRequestMsg first = h.requests.front();
  h.requests.pop_front();
  h.supply->OnChunk(protocol::MakeSceneChunk(packed, first).value());
  ASSERT_GT(h.requests.size(), 1u);
  protocol::SceneChunkMsg bad = protocol::MakeSceneChunk(packed, h.requests.front()).value();
  h.requests.pop_front();
  bad.total_size += 1;
  h.supply->OnChunk(bad);
  ASSERT_EQ(h.failures.size(), 1u);
  // The answers still in flight belong to the dead fetch; a new one starts clean after them.
  std::deque<protocol::SceneRequestMsg> late = std::move(h.requests);
  h.requests.clear();
  ASSERT_TRUE(h.supply->Want(hash).ok());
  for (const auto& request : late)
    h.supply->OnChunk(protocol::MakeSceneChunk(packed, request).value());
  h.Serve(blob);
  ASSERT_TRUE(RunUntil(h.loop, [&] { return !h.ready.empty(); }));
  EXPECT_EQ(h.failures.size(), 1u);
}

TEST(SceneSupplyTest, AChunkNobodyAskedForIsIgnored) {
  const std::vector<uint8_t> blob = codec::EncodePatchScene(testing::BoxScene(2));
  const protocol::PackedScene packed = protocol::PackScene(blob);
  const protocol::SceneHash hash = packed.hash;
  Harness h(std::nullopt);
  const protocol::SceneRequestMsg request{hash, 0, protocol::kMaxSceneChunkBytes};
  h.supply->OnChunk(protocol::MakeSceneChunk(packed, request).value());  // no fetch at all
  ASSERT_TRUE(h.supply->Want(hash).ok());
  h.Serve(blob);
  h.supply->OnChunk(protocol::MakeSceneChunk(packed, request).value());  // one answer too many
  ASSERT_TRUE(h.RunUntilSettled());
  EXPECT_EQ(h.ready.size(), 1u);
  EXPECT_TRUE(h.failures.empty());
}

// A display step's point context on `scene`: direct light only, or gathering with made-up but
// valid per-patch values.
std::vector<uint8_t> PointContextBlob(const PatchScene& scene, bool gathers) {
  PointContext context;
  context.rays_per_point = 4;
  context.rays_per_light = 2;
  if (gathers) {
    const size_t n = scene.patches.size();
    context.outgoing.assign(n, Rgb{0.25, 0.5, 0.75});
    context.corner_offsets.assign(n, {Rgb{0.01, 0, 0}, Rgb{0, 0.01, 0}, Rgb{}, Rgb{}});
    context.bounced.assign(n, Rgb{0.1, 0.1, 0.1});
  }
  return codec::EncodePointContext(codec::EncodePatchScene(scene), context);
}

TEST(SceneSupplyTest, APointContextIsFetchedInChunksPreparedAndKeptButNotSaved) {
  ScratchDir dir;
  const PatchScene scene = testing::VariedBoxScene(testing::kBigBox);
  const std::vector<uint8_t> blob = PointContextBlob(scene, /*gathers=*/true);
  ASSERT_GT(protocol::PackScene(blob).compressed.size(), 2 * protocol::kMaxSceneChunkBytes)
      << "the compressed context should take 3+ chunks";
  const protocol::SceneHash hash = protocol::HashScene(blob);
  Harness h(SceneStore::Open(dir.path()).value());
  ASSERT_TRUE(h.supply->Want(hash, SceneSupply::Blob::kPointContext).ok());
  EXPECT_EQ(h.requests.size(), 1u);  // straight to the master: contexts are not on disk
  h.Serve(blob);
  EXPECT_GT(h.served, 2);
  ASSERT_TRUE(h.RunUntilSettled());
  ASSERT_TRUE(h.failures.empty()) << h.failures[0].second;
  EXPECT_TRUE(h.ready.empty());
  ASSERT_EQ(h.contexts.size(), 1u);
  EXPECT_EQ(h.contexts[0]->hash, hash);
  EXPECT_EQ(h.contexts[0]->patch_count(), scene.patches.size());
  EXPECT_EQ(h.supply->FindContext(hash), h.contexts[0]);
  EXPECT_EQ(h.supply->Find(hash), nullptr);  // not a scene
  ASSERT_TRUE(RunUntil(h.loop, [&] { return h.supply->busy() == 0; }));
  EXPECT_NE(SceneStore::Open(dir.path()).value().Load(hash).outcome,
            SceneStore::LoadOutcome::kFound);
}

TEST(SceneSupplyTest, TheLastTwoPointContextsStayInMemory) {
  Harness h(std::nullopt);
  std::vector<protocol::SceneHash> hashes;
  for (int n : {2, 3, 4}) {
    const std::vector<uint8_t> blob = PointContextBlob(testing::BoxScene(n), /*gathers=*/false);
    hashes.push_back(protocol::HashScene(blob));
    ASSERT_TRUE(h.supply->Want(hashes.back(), SceneSupply::Blob::kPointContext).ok());
    h.Serve(blob);
    ASSERT_TRUE(RunUntil(h.loop, [&] { return h.contexts.size() == hashes.size(); }));
  }
  EXPECT_EQ(h.supply->FindContext(hashes[0]), nullptr);
  EXPECT_NE(h.supply->FindContext(hashes[1]), nullptr);
  EXPECT_NE(h.supply->FindContext(hashes[2]), nullptr);
}

TEST(SceneSupplyTest, ADamagedPointContextIsRefusedAndMayBeFetchedAgain) {
  const std::vector<uint8_t> blob = PointContextBlob(testing::BoxScene(3), /*gathers=*/true);
  const protocol::SceneHash hash = protocol::HashScene(blob);
  std::vector<uint8_t> tampered = blob;
  tampered[tampered.size() / 2] ^= 1;  // the same size, another SHA-256
  Harness h(std::nullopt);
  ASSERT_TRUE(h.supply->Want(hash, SceneSupply::Blob::kPointContext).ok());
  const protocol::PackedScene packed = protocol::PackScene(tampered);
  while (!h.requests.empty()) {
    protocol::SceneChunkMsg chunk = protocol::MakeSceneChunk(packed, h.requests.front()).value();
    h.requests.pop_front();
    chunk.scene_hash = hash;
    h.supply->OnChunk(chunk);
  }
  ASSERT_TRUE(h.RunUntilSettled());
  ASSERT_EQ(h.failures.size(), 1u);
  EXPECT_EQ(h.failures[0].first, protocol::LeaseReturnReason::kFailed);
  EXPECT_NE(h.failures[0].second.find("SHA-256"), std::string::npos) << h.failures[0].second;
  EXPECT_TRUE(h.contexts.empty());
  ASSERT_TRUE(h.supply->Want(hash, SceneSupply::Blob::kPointContext).ok());
  h.Serve(blob);
  ASSERT_TRUE(RunUntil(h.loop, [&] { return !h.contexts.empty(); }));
  EXPECT_EQ(h.failures.size(), 1u);
}

TEST(SceneSupplyTest, APointContextThatDoesNotDecodeIsRememberedAndNotFetchedAgain) {
  // Verified by its hash, but a scene's blob, not a point context's.
  const std::vector<uint8_t> blob = codec::EncodePatchScene(testing::BoxScene(2));
  const protocol::SceneHash hash = protocol::HashScene(blob);
  Harness h(std::nullopt);
  ASSERT_TRUE(h.supply->Want(hash, SceneSupply::Blob::kPointContext).ok());
  h.Serve(blob);
  ASSERT_TRUE(h.RunUntilSettled());
  ASSERT_EQ(h.failures.size(), 1u);
  EXPECT_EQ(h.failures[0].first, protocol::LeaseReturnReason::kFailed);
  EXPECT_TRUE(h.contexts.empty());
  const Status again = h.supply->Want(hash, SceneSupply::Blob::kPointContext);
  ASSERT_FALSE(again.ok());
  EXPECT_NE(again.error().find("point context"), std::string::npos) << again.error();
  EXPECT_TRUE(h.requests.empty());
}

}  // namespace
}  // namespace radfarm::agent
