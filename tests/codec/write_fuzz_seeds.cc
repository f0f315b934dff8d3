// Writes the job bundle, job solution, display blob and point context fuzzers' seed corpora
// (tests/codec/fuzz_corpus/, see docs/FUZZING.md) from the shipped scenes: run by
// scripts/make-fuzz-seeds after a schema change.
//   codec_fuzz_seed_writer SCENES_DIR OUT_DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "codec/display_blob.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/patch_scene_codec.h"
#include "codec/point_context_blob.h"
#include "input/scene_loader.h"
#include "job/job.h"

namespace {

using radfarm::codec::JobBundle;
using radfarm::codec::JobSolution;

void WriteBlob(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// A solution with a few patches of each sign and the stats' strings set, so every field has bytes.
JobSolution SampleSolution(std::vector<uint8_t> bundle, bool with_scene) {
  JobSolution solution;
  solution.bundle = std::move(bundle);
  solution.radiosity = {{0.5, 0.25, 0.125}, {1, 2, 3}, {0, 0, 0}};
  solution.unshot = {{0.01, -0.02, 0.03}, {0, 0, 0}, {-1, 0, 1}};
  solution.stats.rays = 4096;
  solution.stats.rounds = 3;
  solution.stats.patches = 3;
  solution.stats.sampler = "sobol";
  solution.stats.stop_reason = "converged";
  if (with_scene) solution.scene = {1, 2, 3, 4};
  return solution;
}

// A display of three patches, with its front-only flags or without (no patch two-sided), after
// the patch count the fuzzer decodes it against (display_blob_fuzzer.cc).
std::vector<uint8_t> SampleDisplaySeed(bool front_only) {
  radfarm::Display d;
  d.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1e-300}, {1, 1, -2.5}};
  d.mesh.radiance = {{0.1, 0.2, 0.3}, {1, 2, 3}, {0, 0, 0}, {5e-7, 0.5, 1.0 / 3}};
  d.mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
  d.mesh.triangle_patch = {0, 2};
  if (front_only) d.mesh.patch_front_only = {true, false, true};
  d.stats.points = 12;
  d.stats.rays = 1u << 20;
  d.stats.levels = 2;
  std::vector<uint8_t> seed = {3};
  const std::vector<uint8_t> blob = radfarm::codec::EncodeDisplay(d);
  seed.insert(seed.end(), blob.begin(), blob.end());
  return seed;
}

// A point context over two triangles, gathering or not (point_context_fuzzer.cc).
std::vector<uint8_t> SamplePointContextSeed(bool gathers) {
  radfarm::PatchScene scene;
  scene.material_names = {"white", "lamp"};
  for (int k = 0; k < 2; ++k) {
    radfarm::Patch p;
    p.corners = {radfarm::Vec3{0, double(k), 0}, radfarm::Vec3{1, double(k), 0},
                 radfarm::Vec3{0, double(k), 1}, radfarm::Vec3{}};
    p.normal = {0, k == 0 ? 1.0 : -1.0, 0};
    p.centre = {1.0 / 3, double(k), 1.0 / 3};
    p.area = 0.5;
    p.reflectance = {0.5, 0.5, 0.5};
    if (k == 1) p.emission = {2, 2, 2};
    p.material = uint32_t(k);
    scene.patches.push_back(p);
  }
  radfarm::PointContext context;
  context.rays_per_point = 64;
  if (gathers) {
    context.rays_per_light = 16;
    context.outgoing = {{0.1, 0.2, 0.3}, {0, 0, 0}};
    context.corner_offsets = {{radfarm::Rgb(0.5, 0, 0), {}, {}, {}}, {}};
    context.bounced = {{0.01, 0.02, 0.03}, {}};
  }
  return radfarm::codec::EncodePointContext(radfarm::codec::EncodePatchScene(scene), context);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SCENES_DIR OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path scenes = argv[1], out = argv[2];
  std::filesystem::create_directories(out / "job_bundle");
  std::filesystem::create_directories(out / "job_solution");
  std::filesystem::create_directories(out / "display_blob");
  WriteBlob(out / "display_blob" / "two-sided.bin", SampleDisplaySeed(true));
  WriteBlob(out / "display_blob" / "one-sided.bin", SampleDisplaySeed(false));
  std::filesystem::create_directories(out / "point_context");
  WriteBlob(out / "point_context" / "direct.bin", SamplePointContextSeed(false));
  WriteBlob(out / "point_context" / "gathering.bin", SamplePointContextSeed(true));
  // Small scenes of each kind: OBJ with and without a job file, glTF and .glb, lights and cameras.
  const char* jobs[] = {"cornell-box.toml",      "seed-room.toml",  "furnace.obj",
                        "cornell-box-lamp.toml", "cornell-box.glb", "hard-shadow.toml"};
  bool first = true;
  for (const char* name : jobs) {
    auto job = radfarm::LoadJob((scenes / name).string());
    if (!job) return std::fprintf(stderr, "%s\n", job.error().c_str()), 1;
    auto scene = radfarm::LoadScene(job->scene_path);
    if (!scene) return std::fprintf(stderr, "%s\n", scene.error().c_str()), 1;
    // Paths as the farm sees them: relative to nothing on this machine.
    job->scene_path = std::filesystem::path(job->scene_path).filename().string();
    scene->path = job->scene_path;
    const std::vector<uint8_t> bundle = radfarm::codec::EncodeJobBundle({*job, *scene});
    const std::string stem = std::filesystem::path(name).stem().string() +
                             std::filesystem::path(name).extension().string().replace(0, 1, "-");
    WriteBlob(out / "job_bundle" / (stem + ".bin"), bundle);
    WriteBlob(out / "job_solution" / (stem + ".bin"),
              radfarm::codec::EncodeJobSolution(SampleSolution(bundle, first)));
    first = false;
  }
  return 0;
}
