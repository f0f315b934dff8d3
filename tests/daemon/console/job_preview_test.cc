// The status page's preview of a running job shows what `render` would: a closed room's early
// checkpoint seen from inside the room, not one wall in a black frame (a running building's
// preview was black until late).
#include "daemon/console/job_preview.h"

#include <gtest/gtest.h>
#include <png.h>

#include <string>
#include <vector>

#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "input/scene_loader.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"

namespace radfarm::daemon {
namespace {

struct Pixels {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

Pixels DecodePng(const std::string& png) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  Pixels out;
  if (!png_image_begin_read_from_memory(&image, png.data(), png.size())) return out;
  image.format = PNG_FORMAT_RGB;
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) return {};
  out.width = image.width;
  out.height = image.height;
  return out;
}

// A job's checkpoint after a few rounds: a ray budget stops the solve early, as a running job's
// latest checkpoint is.
std::vector<uint8_t> EarlyCheckpoint(const std::string& job_file) {
  Result<Job> job = LoadJob(job_file);
  EXPECT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadScene(job->scene_path);
  EXPECT_TRUE(scene.ok()) << scene.error();
  job->mesh.patch_size = 0.2;  // a coarser mesh: a quick test
  Result<PatchMesh> mesh = PatchMesh::Build(*scene, job->mesh, nullptr);
  EXPECT_TRUE(mesh.ok()) << mesh.error();
  SolverSettings settings = job->solver;
  settings.max_rays = 2'000'000;
  const SolveResult solved = Solve(mesh->patch_scene(), settings);
  return codec::EncodeJobSolution({codec::EncodeJobBundle({*job, *scene}),
                                   solved.radiosity,
                                   solved.unshot,
                                   solved.stats,
                                   {},
                                   {}});
}

TEST(JobPreviewTest, AClosedRoomsEarlyPreviewShowsTheRoomFromInside) {
  const std::vector<uint8_t> solution =
      EarlyCheckpoint(RADFARM_SOURCE_DIR "/scenes/desk-on-floor.toml");
  Result<std::string> png = RenderPreviewPng(solution);
  ASSERT_TRUE(png.ok()) << png.error();
  const Pixels image = DecodePng(*png);
  ASSERT_GT(image.width, 0u);
  EXPECT_EQ(std::max(image.width, image.height), kPreviewPixels);
  size_t black = 0;
  double sum = 0;
  for (size_t i = 0; i < image.rgb.size(); i += 3) {
    const int brightest = std::max({image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]});
    black += brightest < 8;
    sum += brightest;
  }
  const size_t pixels = image.rgb.size() / 3;
  // From outside, the walls' backs fill a black frame; from inside, the lit room fills it.
  EXPECT_LT(double(black) / double(pixels), 0.02) << black << " black pixels of " << pixels;
  EXPECT_GT(sum / double(pixels), 40) << "mean of the brightest channel";
}

}  // namespace
}  // namespace radfarm::daemon
