#include "codec/job_bundle.h"

#include <gtest/gtest.h>

#include <limits>

#include "base/text_file.h"
#include "codec/patch_scene_codec.h"
#include "input/ies_file.h"
#include "input/scene_loader.h"
#include "job/job_lamp.h"
#include "job/job_sky.h"
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

// The lamp-lit box (scenes/cornell-box-lamp.gltf): its lamps reach the master in the bundle.
TEST(JobBundleTest, CarriesPunctualLights) {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box-lamp.toml");
  ASSERT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadScene(job->scene_path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->lights.size(), 3u);
  const JobBundle bundle{*job, *scene};
  Result<JobBundle> back = DecodeJobBundle(EncodeJobBundle(bundle));
  ASSERT_TRUE(back.ok()) << back.error();
  ASSERT_EQ(back->scene.lights.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back->scene.lights[i].kind, scene->lights[i].kind) << i;
    EXPECT_EQ(back->scene.lights[i].position, scene->lights[i].position) << i;
    EXPECT_EQ(back->scene.lights[i].direction, scene->lights[i].direction) << i;
    EXPECT_EQ(back->scene.lights[i].intensity, scene->lights[i].intensity) << i;
  }
  EXPECT_EQ(MeshBlob(*back), MeshBlob(bundle)) << "the meshed scene carries them too";
}

// The daylight example (scenes/daylit-room.toml): its sky reaches the master in the bundle and the
// meshed scene; a clear sky's sun rides as a punctual sun.
TEST(JobBundleTest, CarriesTheSky) {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/daylit-room.toml");
  ASSERT_TRUE(job.ok()) << job.error();
  // Nothing in the room emits: the job's sky lights it, as its lamps may.
  Result<InputScene> scene =
      LoadScene(job->scene_path, kDefaultMaxInputFileBytes, 0, FileReach::kSceneTree, true);
  ASSERT_TRUE(scene.ok()) << scene.error();
  const std::vector<uint8_t> without = EncodeJobBundle({*job, *scene});
  scene->sky = SkyOf(job->sky);
  ASSERT_TRUE(scene->sky.present());
  const JobBundle bundle{*job, *scene};
  const std::vector<uint8_t> with = EncodeJobBundle(bundle);
  EXPECT_GT(with.size(), without.size());
  Result<JobBundle> back = DecodeJobBundle(with);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->scene.sky, scene->sky);
  const std::vector<uint8_t> meshed = MeshBlob(*back);
  EXPECT_EQ(meshed, MeshBlob(bundle));
  Result<PatchScene> patches = DecodePatchScene(meshed);
  ASSERT_TRUE(patches.ok()) << patches.error();
  EXPECT_EQ(patches->sky, scene->sky) << "the meshed scene carries it too";
}

// The IES example (scenes/ies-downlights.toml): its lamps, hung as render and submit hang them,
// reach the master with their candela tables, and the meshed scene the agents get carries them.
TEST(JobBundleTest, CarriesIesLampsWithTheirTables) {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/ies-downlights.toml");
  ASSERT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene =
      LoadScene(job->scene_path, kDefaultMaxInputFileBytes, 0, FileReach::kSceneTree, true);
  ASSERT_TRUE(scene.ok()) << scene.error();
  Result<std::string> text = ReadTextFile(RADFARM_SOURCE_DIR "/scenes/ies-downlights.ies");
  ASSERT_TRUE(text.ok()) << text.error();
  Result<IesPhotometry> ies = ParseIes(*text, "ies-downlights.ies");
  ASSERT_TRUE(ies.ok()) << ies.error();
  ASSERT_EQ(job->lamps.size(), 4u);
  for (const JobLamp& lamp : job->lamps) {
    scene->lights.push_back(
        MakePhotometricLight(lamp.position, lamp.aim, LampReference(lamp), {1, 1, 1}, ies->table));
  }
  const JobBundle bundle{*job, *scene};
  const std::vector<uint8_t> blob = EncodeJobBundle(bundle);
  Result<JobBundle> back = DecodeJobBundle(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(EncodeJobBundle(*back), blob);
  ASSERT_EQ(back->scene.lights.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    const PunctualLight& b = back->scene.lights[i];
    EXPECT_EQ(b.kind, PunctualKind::kPhotometric) << i;
    EXPECT_EQ(b.position, scene->lights[i].position) << i;
    EXPECT_EQ(b.reference, scene->lights[i].reference) << i;
    ASSERT_NE(b.table, nullptr) << i;
    EXPECT_EQ(b.table->candela, ies->table.candela) << i;
    EXPECT_EQ(b.table_lumens, scene->lights[i].table_lumens) << i;
  }
  EXPECT_EQ(MeshBlob(*back), MeshBlob(bundle)) << "the meshed scene carries them too";
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
  // Hostile scenes, threads: a bundle's threads were not range-checked as the job file's are.
  b = good;
  b.job.solver.threads = kMaxSolverThreads + 1;
  expect_error(b, "solver.threads");
  b.job.solver.threads = kMaxSolverThreads;
  EXPECT_TRUE(DecodeJobBundle(EncodeJobBundle(b)).ok());
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

TEST(JobBundleTest, CarriesTheRefineKeys) {
  const JobBundle adaptive = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box-adaptive.toml");
  ASSERT_TRUE(adaptive.job.refine.enabled);
  JobBundle b = adaptive;
  b.job.refine.tolerance = 0.125;
  b.job.refine.min_element_size = 7.5;
  b.job.refine.max_elements = 12345;
  const std::vector<uint8_t> blob = EncodeJobBundle(b);
  Result<JobBundle> back = DecodeJobBundle(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_TRUE(back->job.refine.enabled);
  EXPECT_EQ(back->job.refine.tolerance, 0.125);
  EXPECT_EQ(back->job.refine.min_element_size, 7.5);
  EXPECT_EQ(back->job.refine.max_elements, 12345u);
  EXPECT_EQ(EncodeJobBundle(*back), blob);

  // Refinement off: the bundle is the one written before the refine table existed (same bytes,
  // same hash, so a --db store made then still finds its job), and decodes to the defaults.
  JobBundle off = adaptive;
  off.job.refine = RefineSettings{};
  JobBundle off_but_tuned = off;
  off_but_tuned.job.refine.tolerance = 0.5;
  EXPECT_EQ(EncodeJobBundle(off_but_tuned), EncodeJobBundle(off));
  EXPECT_NE(EncodeJobBundle(off), blob);
  Result<JobBundle> plain = DecodeJobBundle(EncodeJobBundle(off));
  ASSERT_TRUE(plain.ok()) << plain.error();
  EXPECT_FALSE(plain->job.refine.enabled);
  EXPECT_EQ(plain->job.refine.tolerance, RefineSettings{}.tolerance);
}

TEST(JobBundleTest, RejectsBadRefineValues) {
  const JobBundle good = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box-adaptive.toml");
  const auto expect_error = [](const JobBundle& b, const char* words) {
    Result<JobBundle> r = DecodeJobBundle(EncodeJobBundle(b));
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.error().find(words), std::string::npos) << r.error();
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {0.0, -0.25, nan, inf}) {
    SCOPED_TRACE(bad);
    JobBundle b = good;
    b.job.refine.tolerance = bad;
    expect_error(b, "mesh.refine_tolerance");
  }
  for (double bad : {-1.0, nan, inf}) {
    SCOPED_TRACE(bad);
    JobBundle b = good;
    b.job.refine.min_element_size = bad;
    expect_error(b, "mesh.min_element_size");
  }
  JobBundle b = good;
  b.job.refine.max_elements = uint64_t{1} << 63;
  expect_error(b, "mesh.max_elements");
  b.job.refine.max_elements = (uint64_t{1} << 63) - 1;
  EXPECT_TRUE(DecodeJobBundle(EncodeJobBundle(b)).ok());
}

}  // namespace
}  // namespace radfarm::codec

namespace radfarm::codec {
namespace {

TEST(JobBundleTest, CarriesTheScenesObjectsAndRejectsBadOnes) {
  // The glTF Cornell box: eight objects under the CornellBox node, which scales millimetres.
  JobBundle bundle = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  Result<InputScene> scene = LoadScene(RADFARM_SOURCE_DIR "/scenes/cornell-box.gltf");
  ASSERT_TRUE(scene.ok()) << scene.error();
  bundle.scene = *scene;
  bundle.job.scene_path = scene->path;
  ASSERT_EQ(bundle.scene.objects.size(), 9u);
  Result<JobBundle> back = DecodeJobBundle(EncodeJobBundle(bundle));
  ASSERT_TRUE(back.ok()) << back.error();
  ASSERT_EQ(back->scene.objects.size(), 9u);
  for (size_t o = 0; o < 9; ++o) {
    EXPECT_EQ(back->scene.objects[o].name, bundle.scene.objects[o].name);
    EXPECT_EQ(back->scene.objects[o].parent, bundle.scene.objects[o].parent);
    EXPECT_EQ(back->scene.objects[o].local, bundle.scene.objects[o].local);
    EXPECT_EQ(back->scene.objects[o].world, bundle.scene.objects[o].world);
    EXPECT_EQ(back->scene.objects[o].has_faces, bundle.scene.objects[o].has_faces);
  }
  for (size_t f = 0; f < bundle.scene.faces.size(); ++f) {
    EXPECT_EQ(back->scene.faces[f].object, bundle.scene.faces[f].object);
  }

  JobBundle bad_parent = bundle;
  bad_parent.scene.objects[0].parent = 3;
  Result<JobBundle> r = DecodeJobBundle(EncodeJobBundle(bad_parent));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("parent is not an earlier object"), std::string::npos) << r.error();
  JobBundle bad_face = bundle;
  bad_face.scene.faces[0].object = 9;
  r = DecodeJobBundle(EncodeJobBundle(bad_face));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("object out of range"), std::string::npos) << r.error();
}

TEST(JobBundleTest, CarriesLightmapUvsAndRejectsBadOnes) {
  // The room Blender exported with a second UV map: `radfarm fetch` bakes the same lightmaps.
  Result<InputScene> scene = LoadScene(RADFARM_SOURCE_DIR "/tests/blender/lightmap_room.glb");
  ASSERT_TRUE(scene.ok()) << scene.error();
  JobBundle bundle = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  bundle.scene = *scene;
  bundle.job.scene_path = scene->path;
  size_t with_uv = 0;
  for (const InputFace& f : bundle.scene.faces) with_uv += !f.lightmap_uv.empty();
  ASSERT_GT(with_uv, 0u);
  ASSERT_LT(with_uv, bundle.scene.faces.size());  // the lamp has none
  Result<JobBundle> back = DecodeJobBundle(EncodeJobBundle(bundle));
  ASSERT_TRUE(back.ok()) << back.error();
  for (size_t f = 0; f < bundle.scene.faces.size(); ++f) {
    EXPECT_EQ(back->scene.faces[f].lightmap_uv, bundle.scene.faces[f].lightmap_uv) << f;
  }
  JobBundle bad = bundle;
  for (InputFace& f : bad.scene.faces) {
    if (!f.lightmap_uv.empty()) {
      f.lightmap_uv.pop_back();
      break;
    }
  }
  Result<JobBundle> r = DecodeJobBundle(EncodeJobBundle(bad));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("lightmap UVs not 2 per corner"), std::string::npos) << r.error();
}

// `radfarm fetch` bakes the lightmaps from the bundle's job, so their size must travel with it.
// Unset (0) the fields are not written: bundles stay as they were before they existed.
TEST(JobBundleTest, CarriesTheLightmapSettingsAndRejectsBadOnes) {
  const JobBundle plain = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  ASSERT_EQ(plain.job.lightmap_size, 0u);
  ASSERT_EQ(plain.job.lightmap_texel, 0.0);
  const std::vector<uint8_t> plain_blob = EncodeJobBundle(plain);
  for (const auto& [size, texel] : {std::pair<uint32_t, double>{64, 0}, {8192, 0}, {0, 0.125}}) {
    JobBundle bundle = plain;
    bundle.job.lightmap_size = size;
    bundle.job.lightmap_texel = texel;
    const std::vector<uint8_t> blob = EncodeJobBundle(bundle);
    EXPECT_GT(blob.size(), plain_blob.size());
    Result<JobBundle> back = DecodeJobBundle(blob);
    ASSERT_TRUE(back.ok()) << back.error();
    EXPECT_EQ(back->job.lightmap_size, size);
    EXPECT_EQ(back->job.lightmap_texel, texel);
  }
  Result<JobBundle> back = DecodeJobBundle(plain_blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->job.lightmap_size, 0u);
  EXPECT_EQ(back->job.lightmap_texel, 0.0);

  const auto expect_error = [&plain](uint32_t size, double texel, const char* words) {
    JobBundle bad = plain;
    bad.job.lightmap_size = size;
    bad.job.lightmap_texel = texel;
    Result<JobBundle> r = DecodeJobBundle(EncodeJobBundle(bad));
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.error().find(words), std::string::npos) << r.error();
  };
  expect_error(8, 0, "output.lightmap_size is not 0 (automatic) or in [16, 8192]");
  expect_error(8193, 0, "output.lightmap_size is not 0 (automatic) or in [16, 8192]");
  expect_error(0, -1, "output.lightmap_texel is negative or not finite");
  expect_error(0, std::numeric_limits<double>::infinity(), "output.lightmap_texel");
  expect_error(0, std::numeric_limits<double>::quiet_NaN(), "output.lightmap_texel");
  expect_error(64, 0.5, "output.lightmap_texel is set with output.lightmap_size");
}

// `radfarm fetch` writes the illuminance report from the bundle's job, so its planes travel with
// it; a job without planes keeps its bytes.
TEST(JobBundleTest, CarriesTheIlluminancePlanesAndRejectsBadOnes) {
  const JobBundle plain = LoadBundle(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  ASSERT_TRUE(plain.job.illuminance.empty());
  JobBundle bundle = plain;
  bundle.job.illuminance = {{"desks", 0.8, 0.25, {"Desk*", "table"}}, {"floor", 0, 1, {}}};
  const std::vector<uint8_t> blob = EncodeJobBundle(bundle);
  EXPECT_GT(blob.size(), EncodeJobBundle(plain).size());
  Result<JobBundle> back = DecodeJobBundle(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->job.illuminance, bundle.job.illuminance);

  const auto expect_error = [&plain](std::vector<IlluminancePlane> planes, const char* words) {
    JobBundle bad = plain;
    bad.job.illuminance = std::move(planes);
    Result<JobBundle> r = DecodeJobBundle(EncodeJobBundle(bad));
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.error().find(words), std::string::npos) << r.error();
  };
  expect_error({{"../up", 0.8, 1, {}}}, "illuminance[0] name must be");
  expect_error({{"a", 0.8, 0, {}}}, "illuminance[0] spacing must be finite and > 0");
  expect_error({{"a", std::numeric_limits<double>::quiet_NaN(), 1, {}}},
               "illuminance[0] height must be finite");
  expect_error({{"a", 0.8, 1, {}}, {"a", 1, 1, {}}},
               "illuminance[1] repeats an earlier plane's name");
}

}  // namespace
}  // namespace radfarm::codec
