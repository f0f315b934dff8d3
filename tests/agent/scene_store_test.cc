#include "agent/scene_store.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>

#include "protocol/scene_transfer.h"
#include "tests/agent/agent_process.h"

namespace radfarm::agent {
namespace {

using testing::ReadTextFile;
using testing::ScratchDir;
using testing::WriteTextFile;

std::vector<uint8_t> Blob(const std::string& text) { return {text.begin(), text.end()}; }

TEST(SceneStoreTest, SavesUnderTheHashAndLoadsItBack) {
  ScratchDir dir;
  Result<SceneStore> store = SceneStore::Open(dir.File("state"));
  ASSERT_TRUE(store.ok()) << store.error();
  const std::vector<uint8_t> blob = Blob("a scene blob");
  const protocol::SceneHash hash = protocol::HashScene(blob);
  EXPECT_EQ(store->PathFor(hash),
            dir.File("state") + "/scenes/" + protocol::HashToHex(hash) + ".scene");

  EXPECT_EQ(store->Load(hash).outcome, SceneStore::LoadOutcome::kMissing);
  ASSERT_TRUE(store->Save(hash, blob).ok());
  EXPECT_EQ(ReadTextFile(store->PathFor(hash)), "a scene blob");
  SceneStore::Loaded loaded = store->Load(hash);
  EXPECT_EQ(loaded.outcome, SceneStore::LoadOutcome::kFound);
  EXPECT_EQ(loaded.blob, blob);
  // No temporary file is left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(store->scenes_dir()),
                          std::filesystem::directory_iterator()),
            1);
}

// Write's bytes can be read from the temporary at once; the scene is in place only after Commit,
// and a writer dropped uncommitted leaves nothing.
TEST(SceneStoreTest, AWrittenSceneIsReadableAtOnceAndInPlaceOnlyOnceCommitted) {
  ScratchDir dir;
  const SceneStore store = SceneStore::Open(dir.File("state")).value();
  const std::vector<uint8_t> blob = Blob("a scene blob");
  const protocol::SceneHash hash = protocol::HashScene(blob);
  {
    Result<AtomicFileWriter> dropped = store.Write(hash, blob);
    ASSERT_TRUE(dropped.ok()) << dropped.error();
    EXPECT_EQ(ReadTextFile(dropped->temporary_path()), "a scene blob");
  }
  EXPECT_TRUE(std::filesystem::is_empty(store.scenes_dir()));
  Result<AtomicFileWriter> written = store.Write(hash, blob);
  ASSERT_TRUE(written.ok()) << written.error();
  EXPECT_EQ(ReadTextFile(written->temporary_path()), "a scene blob");
  EXPECT_EQ(store.Load(hash).outcome, SceneStore::LoadOutcome::kMissing);
  ASSERT_TRUE(written->Commit().ok());
  EXPECT_EQ(store.Load(hash).blob, blob);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(store.scenes_dir()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(SceneStoreTest, AFileWhoseHashIsNotItsNameIsDeleted) {
  ScratchDir dir;
  Result<SceneStore> store = SceneStore::Open(dir.path());
  ASSERT_TRUE(store.ok()) << store.error();
  const std::vector<uint8_t> blob = Blob("the real scene");
  const protocol::SceneHash hash = protocol::HashScene(blob);
  WriteTextFile(store->PathFor(hash), "the real scenf");  // one bit flipped on disk

  SceneStore::Loaded loaded = store->Load(hash);
  EXPECT_EQ(loaded.outcome, SceneStore::LoadOutcome::kCorrupt);
  EXPECT_TRUE(loaded.blob.empty());
  EXPECT_NE(loaded.detail.find(store->PathFor(hash)), std::string::npos) << loaded.detail;
  EXPECT_NE(loaded.detail.find("deleted"), std::string::npos) << loaded.detail;
  EXPECT_FALSE(std::filesystem::exists(store->PathFor(hash)));
  EXPECT_EQ(store->Load(hash).outcome, SceneStore::LoadOutcome::kMissing);
}

TEST(SceneStoreTest, OpenRemovesTemporaryFilesOfACrashedWriter) {
  ScratchDir dir;
  ASSERT_TRUE(SceneStore::Open(dir.path()).ok());
  const std::string stale = dir.File("scenes/abc.scene.tmp.123.4");    // WriteFileAtomically's
  const std::string older = dir.File("scenes/abc.scene.tmp-123-456");  // older agents' temporaries
  const std::string kept = dir.File("scenes/notes.txt");
  WriteTextFile(stale, "half a scene");
  WriteTextFile(older, "half a scene");
  WriteTextFile(kept, "not ours");
  ASSERT_TRUE(SceneStore::Open(dir.path()).ok());
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_FALSE(std::filesystem::exists(older));
  EXPECT_TRUE(std::filesystem::exists(kept));
}

// An agent started by hand under umask 022 left its scene cache world-readable.
TEST(SceneStoreTest, TheCacheIsPrivateWhateverTheUmask) {
  ScratchDir dir;
  const mode_t old = umask(022);
  Result<SceneStore> store = SceneStore::Open(dir.File("state"));
  const std::vector<uint8_t> blob = Blob("a scene blob");
  const protocol::SceneHash hash = protocol::HashScene(blob);
  const bool saved = store.ok() && store->Save(hash, blob).ok();
  umask(old);
  ASSERT_TRUE(store.ok()) << store.error();
  ASSERT_TRUE(saved);
  const auto mode = [](const std::string& path) {
    struct stat st {};
    EXPECT_EQ(stat(path.c_str(), &st), 0) << path;
    return st.st_mode & 0777;
  };
  EXPECT_EQ(mode(dir.File("state")), 0700u);
  EXPECT_EQ(mode(store->scenes_dir()), 0700u);
  EXPECT_EQ(mode(store->PathFor(hash)), 0600u);
}

TEST(SceneStoreTest, AnUnusableStateDirectoryIsNamed) {
  ScratchDir dir;
  WriteTextFile(dir.File("file"), "not a directory");
  Result<SceneStore> store = SceneStore::Open(dir.File("file"));
  ASSERT_FALSE(store.ok());
  EXPECT_NE(store.error().find(dir.File("file")), std::string::npos) << store.error();
}

}  // namespace
}  // namespace radfarm::agent
