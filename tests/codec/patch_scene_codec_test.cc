#include "codec/patch_scene_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "input/input_scene.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"

namespace radfarm::codec {
namespace {

PatchScene CornellPatches() {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  EXPECT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  EXPECT_TRUE(scene.ok()) << scene.error();
  Result<PatchMesh> mesh = PatchMesh::Build(*scene, job->mesh, nullptr);
  EXPECT_TRUE(mesh.ok()) << mesh.error();
  return mesh->patch_scene();
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool SameBits(const Vec3& a, const Vec3& b) {
  return SameBits(a.x, b.x) && SameBits(a.y, b.y) && SameBits(a.z, b.z);
}
bool SameBits(const Rgb& a, const Rgb& b) {
  return SameBits(a.r, b.r) && SameBits(a.g, b.g) && SameBits(a.b, b.b);
}

TEST(PatchSceneCodecTest, RoundTripsEveryBitAndIsDeterministic) {
  const PatchScene scene = CornellPatches();
  ASSERT_GT(scene.patches.size(), 100u);
  const std::vector<uint8_t> blob = EncodePatchScene(scene);
  EXPECT_EQ(blob, EncodePatchScene(scene));
  Result<PatchScene> back = DecodePatchScene(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  ASSERT_EQ(back->patches.size(), scene.patches.size());
  EXPECT_EQ(back->material_names, scene.material_names);
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& a = scene.patches[i];
    const Patch& b = back->patches[i];
    ASSERT_EQ(a.corner_count, b.corner_count);
    for (int k = 0; k < a.corner_count; ++k) EXPECT_TRUE(SameBits(a.corners[k], b.corners[k]));
    EXPECT_TRUE(SameBits(a.normal, b.normal));
    EXPECT_TRUE(SameBits(a.centre, b.centre));
    EXPECT_TRUE(SameBits(a.area, b.area));
    EXPECT_TRUE(SameBits(a.reflectance, b.reflectance));
    EXPECT_TRUE(SameBits(a.emission, b.emission));
    EXPECT_EQ(a.surface, b.surface);
    EXPECT_EQ(a.material, b.material);
  }
  EXPECT_EQ(EncodePatchScene(*back), blob);
}

// DecodePatches (an agent's decoder) hands over the same patches, in order, as DecodePatchScene
// keeps, and refuses what it refuses.
TEST(PatchSceneCodecTest, DecodePatchesVisitsEveryPatchInOrder) {
  const PatchScene scene = CornellPatches();
  const std::vector<uint8_t> blob = EncodePatchScene(scene);
  std::vector<Patch> visited;
  Result<uint32_t> count = DecodePatches(blob, [&](const Patch& p, uint32_t index, uint32_t n) {
    EXPECT_EQ(index, visited.size());
    EXPECT_EQ(n, scene.patches.size());
    visited.push_back(p);
  });
  ASSERT_TRUE(count.ok()) << count.error();
  EXPECT_EQ(*count, scene.patches.size());
  ASSERT_EQ(visited.size(), scene.patches.size());
  PatchScene back;
  back.patches = visited;
  back.material_names = scene.material_names;
  back.lights = scene.lights;
  EXPECT_EQ(EncodePatchScene(back), blob);
  std::vector<uint8_t> truncated(blob.begin(), blob.end() - 16);
  EXPECT_FALSE(DecodePatches(truncated, [](const Patch&, uint32_t, uint32_t) {}).ok());
}

// DecodeAcceptedPatches (an agent's reads of its own copy of a blob it checked) hands over the
// same patches as DecodePatches, and still checks their values.
TEST(PatchSceneCodecTest, DecodeAcceptedPatchesVisitsWhatDecodePatchesVisits) {
  PatchScene scene = CornellPatches();
  const std::vector<uint8_t> blob = EncodePatchScene(scene);
  std::vector<Patch> checked, accepted;
  ASSERT_TRUE(
      DecodePatches(blob, [&](const Patch& p, uint32_t, uint32_t) { checked.push_back(p); }).ok());
  Result<uint32_t> count =
      DecodeAcceptedPatches(blob, [&](const Patch& p, uint32_t index, uint32_t n) {
        EXPECT_EQ(index, accepted.size());
        EXPECT_EQ(n, scene.patches.size());
        accepted.push_back(p);
      });
  ASSERT_TRUE(count.ok()) << count.error();
  EXPECT_EQ(*count, scene.patches.size());
  PatchScene a, b;
  a.patches = checked;
  b.patches = accepted;
  a.material_names = b.material_names = scene.material_names;
  EXPECT_EQ(EncodePatchScene(b), EncodePatchScene(a));
  scene.patches[1].area = -1;
  const std::vector<uint8_t> bad = EncodePatchScene(scene);
  EXPECT_FALSE(DecodeAcceptedPatches(bad, [](const Patch&, uint32_t, uint32_t) {}).ok());
}

TEST(PatchSceneCodecTest, DecodesFromAnUnalignedBuffer) {
  const std::vector<uint8_t> blob = EncodePatchScene(CornellPatches());
  std::vector<uint8_t> shifted(blob.size() + 1);
  std::memcpy(shifted.data() + 1, blob.data(), blob.size());
  EXPECT_TRUE(DecodePatchScene(std::span(shifted).subspan(1)).ok());
}

TEST(PatchSceneCodecTest, RejectsTruncatedAndCorruptBlobsWithoutCrashing) {
  const std::vector<uint8_t> blob = EncodePatchScene(CornellPatches());
  EXPECT_FALSE(DecodePatchScene({}).ok());
  for (size_t n : {size_t{4}, size_t{8}, blob.size() / 2, blob.size() - 1}) {
    EXPECT_FALSE(DecodePatchScene(std::span(blob).first(n)).ok()) << n;
  }
  std::vector<uint8_t> wrong_id = blob;
  wrong_id[4] = 'X';
  Result<PatchScene> r = DecodePatchScene(wrong_id);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("identifier"), std::string::npos) << r.error();
  // Flip every bit of the first 4 KiB once: decoding either fails cleanly or yields a scene
  // whose every value passed the checks.
  for (size_t byte = 0; byte < std::min<size_t>(blob.size(), 4096); ++byte) {
    std::vector<uint8_t> flipped = blob;
    flipped[byte] ^= uint8_t(1u << (byte % 8));
    Result<PatchScene> d = DecodePatchScene(flipped);
    if (d.ok()) {
      for (const Patch& p : d->patches) ASSERT_TRUE(p.area > 0 && std::isfinite(p.area));
    }
  }
}

TEST(PatchSceneCodecTest, RejectsValuesOutOfRangeNamingThePatch) {
  const PatchScene good = CornellPatches();
  const auto expect_error = [](const PatchScene& scene, const char* words) {
    Result<PatchScene> r = DecodePatchScene(EncodePatchScene(scene));
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.error().find("patch 3"), std::string::npos) << r.error();
    EXPECT_NE(r.error().find(words), std::string::npos) << r.error();
  };
  PatchScene s = good;
  s.patches[3].corners[1].y = std::numeric_limits<double>::quiet_NaN();
  expect_error(s, "non-finite corner");
  s = good;
  s.patches[3].reflectance.g = 1.0;
  expect_error(s, "reflectance");
  s = good;
  s.patches[3].emission.b = -1;
  expect_error(s, "emission");
  s = good;
  s.patches[3].area = 0;
  expect_error(s, "area");
  s = good;
  s.patches[3].material = 999;
  expect_error(s, "material 999");
  s = good;
  s.patches[3].normal = {0, 0, 2};
  expect_error(s, "unit vector");
  s = good;
  s.patches.clear();
  EXPECT_FALSE(DecodePatchScene(EncodePatchScene(s)).ok());
}

// Punctual lights ride in the blob (the master's checkpointed refined scene,
// core/punctual_light.h); a scene without them has the bytes it had before they existed: no
// `lights` field at all.
TEST(PatchSceneCodecTest, CarriesPunctualLightsAndChecksThem) {
  PatchScene scene = CornellPatches();
  const std::vector<uint8_t> without = EncodePatchScene(scene);
  PunctualLight spot;
  spot.kind = PunctualKind::kSpot;
  spot.position = {0.1, 0.2, 0.3};
  spot.direction = {0, -1, 0};
  spot.intensity = {1.5, 2.5, 3.5};
  spot.range = 7;
  spot.inner_cone = 0.25;
  spot.outer_cone = 0.5;
  PunctualLight sun;
  sun.kind = PunctualKind::kSun;
  sun.direction = {0, 0, -1};
  sun.intensity = {100, 100, 100};
  scene.lights = {spot, sun};
  const std::vector<uint8_t> with = EncodePatchScene(scene);
  EXPECT_GT(with.size(), without.size());
  Result<PatchScene> back = DecodePatchScene(with);
  ASSERT_TRUE(back.ok()) << back.error();
  ASSERT_EQ(back->lights.size(), 2u);
  const PunctualLight& b = back->lights[0];
  EXPECT_EQ(b.kind, PunctualKind::kSpot);
  EXPECT_TRUE(SameBits(b.position, spot.position));
  EXPECT_TRUE(SameBits(b.direction, spot.direction));
  EXPECT_TRUE(SameBits(b.intensity, spot.intensity));
  EXPECT_TRUE(SameBits(b.range, spot.range));
  EXPECT_TRUE(SameBits(b.inner_cone, spot.inner_cone));
  EXPECT_TRUE(SameBits(b.outer_cone, spot.outer_cone));
  EXPECT_EQ(back->lights[1].kind, PunctualKind::kSun);
  EXPECT_EQ(EncodePatchScene(*back), with);
  scene.lights[1].intensity.g = -1;
  Result<PatchScene> bad = DecodePatchScene(EncodePatchScene(scene));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "scene blob: light 1 intensity is negative or not finite");
  scene.lights[1].intensity.g = 1;
  scene.lights[1].kind = static_cast<PunctualKind>(7);
  bad = DecodePatchScene(EncodePatchScene(scene));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("light 1 kind 7"), std::string::npos) << bad.error();
}

// The sky rides in the blob as the lamps do (the agents' start and display points light patches
// with it); a scene without one keeps its bytes: no `sky` field at all.
TEST(PatchSceneCodecTest, CarriesTheSkyAndChecksIt) {
  PatchScene scene = CornellPatches();
  const std::vector<uint8_t> without = EncodePatchScene(scene);
  scene.sky = {SkyKind::kCieClear, 4321.5, Normalize(Vec3{0.3, 0.8, -0.5})};
  const std::vector<uint8_t> with = EncodePatchScene(scene);
  EXPECT_GT(with.size(), without.size());
  Result<PatchScene> back = DecodePatchScene(with);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->sky, scene.sky);
  EXPECT_EQ(EncodePatchScene(*back), with);
  scene.sky.zenith = -1;
  Result<PatchScene> bad = DecodePatchScene(EncodePatchScene(scene));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "scene blob: sky sky zenith luminance must be finite and >= 0");
  scene.sky = {static_cast<SkyKind>(9), 1, {0, 1, 0}};
  bad = DecodePatchScene(EncodePatchScene(scene));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("sky kind out of range"), std::string::npos) << bad.error();
}

// A photometric lamp carries its candela table; the decoder checks the table before using it.
TEST(PatchSceneCodecTest, CarriesAPhotometricLampsTableAndChecksIt) {
  PatchScene scene = CornellPatches();
  const CandelaTable table{{0, 45, 90}, {0, 90}, {100, 80, 0, 300, 200, 0}};
  scene.lights = {MakePhotometricLight({0.2, 0.5, 0.2}, {0, -1, 0}, {0, 0, 1}, {2, 2, 2}, table)};
  const std::vector<uint8_t> with = EncodePatchScene(scene);
  Result<PatchScene> back = DecodePatchScene(with);
  ASSERT_TRUE(back.ok()) << back.error();
  ASSERT_EQ(back->lights.size(), 1u);
  const PunctualLight& b = back->lights[0];
  EXPECT_EQ(b.kind, PunctualKind::kPhotometric);
  EXPECT_TRUE(SameBits(b.reference, Vec3{0, 0, 1}));
  ASSERT_NE(b.table, nullptr);
  EXPECT_EQ(b.table->vertical, table.vertical);
  EXPECT_EQ(b.table->horizontal, table.horizontal);
  EXPECT_EQ(b.table->candela, table.candela);
  EXPECT_TRUE(SameBits(b.table_lumens, scene.lights[0].table_lumens));
  EXPECT_EQ(EncodePatchScene(*back), with);
  CandelaTable short_table = table;
  short_table.candela.pop_back();
  scene.lights[0].table = std::make_shared<const CandelaTable>(short_table);
  Result<PatchScene> bad = DecodePatchScene(EncodePatchScene(scene));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "scene blob: light 0 the table has 5 candela values, not 6");
}

}  // namespace
}  // namespace radfarm::codec
