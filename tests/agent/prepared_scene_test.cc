// PrepareScene: what an agent keeps of a fetched scene must trace every batch as the whole scene
// does, whether it reads the patches from its saved copy (the caster streamed from the mapped
// file before the shapes are decoded) or, without one, from the blob.
#include "agent/prepared_scene.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "codec/patch_scene_codec.h"
#include "core/batch_tracer.h"
#include "core/ray_sampler.h"
#include "testing/temp_dir.h"
#include "tests/core/test_scenes.h"

namespace radfarm::agent {
namespace {

PatchScene Scene() {
  PatchScene scene = testing::MakeClosedBox({-1, 0, 2}, {2, 1.5, 4}, 5, {{0.5, 0.5, 0.5}, {}});
  testing::AddDisc({0.5, 0.7, 3}, Normalize(Vec3{0.2, 1, -0.3}), 0.4, 9, {{0.3, 0.3, 0.3}, {}},
                   &scene);
  for (size_t i = 0; i < scene.patches.size(); i += 5) scene.patches[i].two_sided = true;
  scene.material_names = {"grey"};
  return scene;
}

void ExpectSameBatches(const PatchScene& scene, const PreparedScene& prepared) {
  ASSERT_EQ(prepared.patch_count(), scene.patches.size());
  const RayCaster whole(scene);
  const RaySampler sampler(SamplerKind::kSobol, 3, 6.0);
  BatchTracer a(scene, whole, sampler), b(prepared.shapes, *prepared.caster, sampler);
  uint64_t hits = 0;
  for (uint32_t id = 0; id < scene.patches.size(); ++id) {
    const Batch batch{1, id, 0, 400};
    const BatchResult expected = a.Run(batch);
    EXPECT_EQ(b.Run(batch), expected) << "patch " << id;
    hits += expected.hits.size();
  }
  EXPECT_GT(hits, 0u);
}

TEST(PreparedSceneTest, FromTheSavedFileTracesAsTheWholeScene) {
  const PatchScene scene = Scene();
  const std::vector<uint8_t> blob = codec::EncodePatchScene(scene);
  testing::TempDir dir;
  const std::string file = dir.File("scene");
  bool saved = false;
  Result<std::shared_ptr<const PreparedScene>> prepared =
      PrepareScene({}, blob, [&](std::span<const uint8_t> bytes) {
        std::ofstream(file, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        saved = true;
        return file;
      });
  ASSERT_TRUE(prepared.ok()) << prepared.error();
  EXPECT_TRUE(saved);
  ExpectSameBatches(scene, **prepared);
}

TEST(PreparedSceneTest, WithoutAFileTracesAsTheWholeScene) {
  const PatchScene scene = Scene();
  Result<std::shared_ptr<const PreparedScene>> prepared =
      PrepareScene({}, codec::EncodePatchScene(scene));
  ASSERT_TRUE(prepared.ok()) << prepared.error();
  ExpectSameBatches(scene, **prepared);
}

// A file that does not hold the blob (here: shorter) is not read; the blob is.
TEST(PreparedSceneTest, AFileOfAnotherSizeIsNotRead) {
  const PatchScene scene = Scene();
  testing::TempDir dir;
  const std::string file = dir.File("short");
  std::ofstream(file) << "not the scene";
  Result<std::shared_ptr<const PreparedScene>> prepared = PrepareScene(
      {}, codec::EncodePatchScene(scene), [&](std::span<const uint8_t>) { return file; });
  ASSERT_TRUE(prepared.ok()) << prepared.error();
  ExpectSameBatches(scene, **prepared);
}

TEST(PreparedSceneTest, ABadBlobIsRefused) {
  PatchScene scene = Scene();
  scene.patches[3].reflectance = {2, 0, 0};
  EXPECT_FALSE(PrepareScene({}, codec::EncodePatchScene(scene)).ok());
}

}  // namespace
}  // namespace radfarm::agent
