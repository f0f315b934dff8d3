#include "codec/job_bundle.h"

#include <gtest/gtest.h>

#include <limits>

#include "codec/patch_scene_codec.h"
#include "mesh/patch_mesh.h"

namespace radfarm::codec {
namespace {

JobBundle LoadBundle(const std::string& job_path) {
  Result<Job> job = LoadJob(job_path);
  EXPECT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  EXPECT_TRUE(scene.ok()) << scene.error();
  return {*job, *scene};
}

std::vector<uint8_t> MeshBlob(const JobBundle& bundle) {
  Result<PatchMesh> mesh = PatchMesh::Build(bundle.scene, bundle.job.mesh, nullptr);
  EXPECT_TRUE(mesh.ok()) << mesh.error();
  return mesh.ok() ? EncodePatchScene(mesh->patch_scene()) : std::vector<uint8_t>{};
}

TEST(JobBundleTest, MeshingTheDecodedBundleGivesTheSamePatches) {
  for (const char* name : {"cornell-box.toml", "seed-room.toml", "touching-boxes.obj"}) {
    SCOPED_TRACE(name);
    const std::string path = std::string(RADFARM_SOURCE_DIR "/scenes/") + name;
    JobBundle bundle;
    if (path.ends_with(".obj")) {
      Result<Job> job = LoadJob(path);
      ASSERT_TRUE(job.ok()) << job.error();
      Result<InputScene> scene = LoadObjScene(job->scene_path);
      ASSERT_TRUE(scene.ok()) << scene.error();
      bundle = {*job, *scene};
    } else {
      bundle = LoadBundle(path);
    }
    const std::vector<uint8_t> blob = EncodeJobBundle(bundle);
    EXPECT_EQ(blob, EncodeJobBundle(bundle));
    Result<JobBundle> back = DecodeJobBundle(blob);
    ASSERT_TRUE(back.ok()) << back.error();
    EXPECT_EQ(EncodeJobBundle(*back), blob);
    EXPECT_EQ(back->job.scene_path, bundle.job.scene_path);
    EXPECT_EQ(back->job.solver.seed, bundle.job.solver.seed);
    EXPECT_EQ(back->job.solver.max_rays, bundle.job.solver.max_rays);
    EXPECT_EQ(back->job.camera.width, bundle.job.camera.width);
    EXPECT_EQ(MeshBlob(*back), MeshBlob(bundle));
  }
}

TEST(JobBundleTest, RejectsCorruptBlobsAndBadValues) {
  const JobBundle good = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  const std::vector<uint8_t> blob = EncodeJobBundle(good);
  EXPECT_FALSE(DecodeJobBundle(std::span(blob).first(blob.size() / 2)).ok());
  for (size_t byte = 0; byte < std::min<size_t>(blob.size(), 2048); ++byte) {
    std::vector<uint8_t> flipped = blob;
    flipped[byte] ^= 0x40;
    (void)DecodeJobBundle(flipped);  // must not crash (ASan/UBSan builds check)
  }
  const auto expect_error = [](const JobBundle& b, const char* words) {
    Result<JobBundle> r = DecodeJobBundle(EncodeJobBundle(b));
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.error().find(words), std::string::npos) << r.error();
  };
  JobBundle b = good;
  b.scene.faces[2].indices[1] = 1u << 30;
  expect_error(b, "face 2 index out of range");
  b = good;
  b.scene.positions[0].x = std::numeric_limits<double>::infinity();
  expect_error(b, "positions[0]");
  b = good;
  b.scene.materials[0].diffuse.r = 1.5;
  expect_error(b, "reflectance");
  b = good;
  b.job.solver.tolerance = 0;
  expect_error(b, "solver.tolerance");
  b = good;
  b.job.camera.width = 0;
  expect_error(b, "camera.width");
  for (double omega : {0.5, 2.0, std::numeric_limits<double>::infinity(),
                       std::numeric_limits<double>::quiet_NaN()}) {
    b = good;
    b.job.solver.overrelaxation = omega;
    expect_error(b, "solver.overrelaxation");
  }
}

// The master plans rounds from the bundle's settings, so over-relaxation must travel with it. At
// its default of 1 the field is not written: bundles stay as they were before it existed.
TEST(JobBundleTest, CarriesOverrelaxation) {
  JobBundle bundle = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  ASSERT_EQ(bundle.job.solver.overrelaxation, 1.0);
  const std::vector<uint8_t> plain = EncodeJobBundle(bundle);
  bundle.job.solver.overrelaxation = 1.25;
  const std::vector<uint8_t> relaxed = EncodeJobBundle(bundle);
  EXPECT_GT(relaxed.size(), plain.size());
  Result<JobBundle> back = DecodeJobBundle(relaxed);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->job.solver.overrelaxation, 1.25);
  Result<JobBundle> back_plain = DecodeJobBundle(plain);
  ASSERT_TRUE(back_plain.ok()) << back_plain.error();
  EXPECT_EQ(back_plain->job.solver.overrelaxation, 1.0);
}

}  // namespace
}  // namespace radfarm::codec
