// Bounds on what a job may ask for: only regular files as scene inputs, sizes
// checked before reading, and the image's cost (pixels x samples, memory) before anything is
// meshed. Before, `mtllib /dev/zero` or `scene = "/dev/urandom"` ran out of memory, a FIFO hung,
// a 2 GB file cost 66 s and 8.4 GB before its error, and 16384 x 16384 at 1024 samples per pixel
// grew past 14 GB with no progress. Each case: exit 2 and one line naming the file and the limit.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

using testing::CommandResult;
using testing::RunCommand;
using testing::TempDir;

CommandResult Render(const TempDir& dir, const std::string& scene,
                     const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {RADFARM_CLI_PATH, "render",        scene,
                                   "--out",          dir.File("out"), "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  return RunCommand(args);
}

void Write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A job file whose camera is the only thing that differs from the Cornell box's.
std::string JobWithCamera(const TempDir& dir, uint32_t side, uint32_t samples) {
  const std::string job = dir.File("big-image.toml");
  Write(job, "scene = \"" RADFARM_SOURCE_DIR "/scenes/furnace.obj\"\n[camera]\nwidth = " +
                 std::to_string(side) + "\nheight = " + std::to_string(side) +
                 "\nsamples_per_pixel = " + std::to_string(samples) + "\n");
  return job;
}

TEST(RenderBoundsTest, ADeviceAsTheSceneIsRefusedBeforeAnyRead) {
  TempDir dir;
  const std::string job = dir.File("urandom.toml");
  Write(job, "scene = \"/dev/urandom\"\n");
  const CommandResult r = Render(dir, job);
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("/dev/urandom: cannot open: not a regular file (a character device)"),
            std::string::npos)
      << r.err;
}

TEST(RenderBoundsTest, AFifoAsTheSceneIsRefusedInsteadOfHanging) {
  TempDir dir;
  const std::string fifo = dir.File("pipe.obj");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const CommandResult r = Render(dir, fifo);
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("pipe.obj: cannot open: not a regular file (a FIFO)"), std::string::npos)
      << r.err;
}

TEST(RenderBoundsTest, MtllibDevZeroIsAnErrorNotAnEndlessRead) {
  TempDir dir;
  const std::string obj = dir.File("zero.obj");
  Write(obj, "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const CommandResult r = Render(dir, obj);
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("zero.obj:1: mtllib '/dev/zero' is an absolute path"), std::string::npos)
      << r.err;
}

// A sparse 2 GiB file: refused from its size, so the test costs no disk and no time.
TEST(RenderBoundsTest, ASceneOverTheSizeLimitIsRefusedFromItsSize) {
  TempDir dir;
  const std::string big = dir.File("big.obj");
  { std::ofstream(big) << "v 0 0 0\n"; }
  std::filesystem::resize_file(big, uint64_t{2} << 30);
  CommandResult r = Render(dir, big);
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("big.obj: the file is 2147483648 bytes, over the limit of 1073741824 bytes"),
            std::string::npos)
      << r.err;
  // --max-scene-bytes sets the limit, for the MTL files too.
  r = Render(dir, RADFARM_SOURCE_DIR "/scenes/cornell-box.obj", {"--max-scene-bytes", "1K"});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("cornell-box.obj: the file is "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("over the limit of 1024 bytes"), std::string::npos) << r.err;
  Write(dir.File("padded.mtl"),
        std::string(2000, '#') + "\nnewmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  Write(dir.File("small.obj"),
        "mtllib padded.mtl\nusemtl glow\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  r = Render(dir, dir.File("small.obj"), {"--max-scene-bytes", "1K"});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("padded.mtl: the file is 2037 bytes, over the limit of 1024 bytes"),
            std::string::npos)
      << r.err;
}

// A scene whose library lies beside its directory: refused, unless the user says they trust it.
TEST(RenderBoundsTest, FilesOutsideTheScenesDirectoryNeedTheUsersLeave) {
  TempDir dir;
  std::filesystem::create_directory(dir.File("scene"));
  Write(dir.File("shared.mtl"), "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  const std::string obj = dir.File("scene/s.obj");
  Write(obj, "mtllib ../shared.mtl\nusemtl glow\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CommandResult r = Render(dir, obj);
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("s.obj:1: mtllib '../shared.mtl' leads outside the scene's directory"),
            std::string::npos)
      << r.err;
  r = Render(dir, obj, {"--allow-outside-files"});
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.File("out/image.png")));
}

TEST(RenderBoundsTest, AnImageOverThePixelSampleLimitIsRefusedBeforeMeshing) {
  TempDir dir;
  CommandResult r = Render(dir, JobWithCamera(dir, 16384, 1024));
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("big-image.toml: camera: 16384 x 16384 pixels x 1024 samples = "
                       "274877906944 pixel samples, more than the limit of 4294967296; use fewer "
                       "samples_per_pixel or a smaller image"),
            std::string::npos)
      << r.err;
  // Within the sample limit, the image's memory against --max-memory: 16384^2 x 80 bytes.
  r = Render(dir, JobWithCamera(dir, 16384, 1), {"--max-memory", "1G"});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("big-image.toml: camera: a 16384 x 16384 image needs about 20480 MB of "
                       "memory, more than the limit of 1024 MB (--max-memory)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("out/image.png")));
}

// A 0.5 MB PNG declaring 16000 x 16000 16-bit pixels decoded to 2 GB and was copied to 6 GB of
// texels, and --max-memory covered only the output image. A texture's decoded size now counts
// against it, read from the header before anything is decoded: here a 33-byte PNG that declares
// 8000 x 8000 16-bit RGBA pixels.
TEST(RenderBoundsTest, ATextureOverMaxMemoryIsRefusedFromItsHeader) {
  TempDir dir;
  std::string gltf = testing::ReadFile(RADFARM_SOURCE_DIR "/scenes/cornell-box.gltf");
  gltf.insert(gltf.find('{') + 1, "\"images\": [{\"uri\": \"big.png\"}],");
  Write(dir.File("textured.gltf"), gltf);
  std::string png = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1A', '\n', 0, 0, 0, 13};
  png += "IHDR";
  png += std::string{0, 0, 0x1F, 0x40, 0, 0, 0x1F, 0x40, 16, 6, 0, 0, 0, 0, 0, 0, 0};  // 8000^2
  Write(dir.File("big.png"), png);
  const CommandResult r = Render(dir, dir.File("textured.gltf"), {"--max-memory", "256M"});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(r.err.find("textured.gltf: images[0] 'big.png': PNG of 8000 x 8000 pixels (4 x 16-bit "
                       "channels) needs about 489 MB decoded, more than the 256 MB the memory "
                       "limit leaves for textures (--max-memory)"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace radfarm
