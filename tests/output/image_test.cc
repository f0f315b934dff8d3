#include "output/image.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

namespace radfarm {
namespace {

// Eye at the origin looking along +z, 90 degree vertical fov: with a 100-pixel-high image the
// focal length is 50 pixels. Image right is world -x (right = forward x up).
Camera FrontCamera(uint32_t width, uint32_t height, uint32_t spp) {
  Camera camera;
  camera.automatic = false;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, 1};
  camera.up = {0, 1, 0};
  camera.fov_degrees = 90;
  camera.width = width;
  camera.height = height;
  camera.samples_per_pixel = spp;
  return camera;
}

using RadianceFn = std::function<Rgb(const Vec3&)>;

void AddTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const RadianceFn& radiance,
                 DisplayMesh* mesh) {
  const uint32_t base = static_cast<uint32_t>(mesh->positions.size());
  for (const Vec3& p : {a, b, c}) {
    mesh->positions.push_back(p);
    mesh->radiance.push_back(radiance(p));
  }
  mesh->triangles.push_back({base, base + 1, base + 2});
  mesh->triangle_patch.push_back(static_cast<uint32_t>(mesh->triangle_patch.size()));
}

RadianceFn Constant(Rgb value) {
  return [value](const Vec3&) { return value; };
}

// Axis-aligned quad in the plane z = depth(x), as two triangles.
void AddQuad(double half, const std::function<double(double)>& depth, const RadianceFn& radiance,
             DisplayMesh* mesh) {
  const Vec3 p00{-half, -half, depth(-half)}, p10{half, -half, depth(half)};
  const Vec3 p11{half, half, depth(half)}, p01{-half, half, depth(-half)};
  AddTriangle(p00, p10, p11, radiance, mesh);
  AddTriangle(p00, p11, p01, radiance, mesh);
}

double SumRed(const Image& image) {
  double sum = 0;
  for (const Rgb& p : image.pixels) sum += p.r;
  return sum;
}

// The subpixel strata drawn on a pool's threads make the same image, to the bit: overlapping
// triangles at several depths, a ramp of radiance, 16 samples a pixel.
TEST(RenderImageTest, APoolDrawsTheSameBits) {
  DisplayMesh mesh;
  AddQuad(
      0.8, [](double x) { return 2 + 0.3 * x; },
      [](const Vec3& p) {
        return Rgb{p.x + 1, p.y + 1, 0.5};
      },
      &mesh);
  AddQuad(
      0.4, [](double) { return 1.7; }, Constant({0.2, 0.9, 0.4}), &mesh);
  AddTriangle({-1, -1, 1.5}, {0.5, -0.2, 2.5}, {0, 1, 1.9}, Constant({0.7, 0.1, 0.3}), &mesh);
  const Camera camera = FrontCamera(64, 48, 16);
  const Image alone = RenderImage(mesh, camera);
  ThreadPool pool(3);
  const Image pooled = RenderImage(mesh, camera, {}, &pool);
  ASSERT_EQ(alone.pixels.size(), pooled.pixels.size());
  EXPECT_GT(SumRed(alone), 0);
  for (size_t i = 0; i < alone.pixels.size(); ++i) {
    ASSERT_EQ(alone.pixels[i].r, pooled.pixels[i].r) << i;
    ASSERT_EQ(alone.pixels[i].g, pooled.pixels[i].g) << i;
    ASSERT_EQ(alone.pixels[i].b, pooled.pixels[i].b) << i;
  }
}

TEST(RenderImageTest, SingleTriangleCoversItsArea) {
  DisplayMesh mesh;
  AddTriangle({-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0, 0.5, 1}, Constant({2, 2, 2}), &mesh);
  const Image image = RenderImage(mesh, FrontCamera(100, 100, 16));
  ASSERT_EQ(image.width, 100u);
  ASSERT_EQ(image.height, 100u);
  ASSERT_EQ(image.pixels.size(), 10000u);
  // 50 x 50 pixel base and height: 1250 pixels of radiance 2.
  EXPECT_NEAR(SumRed(image) / 2, 1250, 5);
  EXPECT_EQ(image.At(50, 60).r, 2);  // well inside
  EXPECT_EQ(image.At(5, 5).r, 0);    // background
  for (const Rgb& p : image.pixels) {
    EXPECT_GE(p.r, 0);
    EXPECT_LE(p.r, 2 + 1e-12);
  }
}

TEST(RenderImageTest, MoreSamplesConvergeToTheExactArea) {
  DisplayMesh mesh;
  AddTriangle({-0.41, -0.37, 1}, {0.53, -0.29, 1}, {0.07, 0.61, 1}, Constant({1, 1, 1}), &mesh);
  // Shoelace area in pixels (focal 50).
  const double area =
      0.5 * std::fabs((0.53 + 0.41) * (0.61 + 0.37) - (0.07 + 0.41) * (-0.29 + 0.37)) * 2500;
  const double error_4 = std::fabs(SumRed(RenderImage(mesh, FrontCamera(100, 100, 4))) - area);
  const double error_64 = std::fabs(SumRed(RenderImage(mesh, FrontCamera(100, 100, 64))) - area);
  EXPECT_LT(error_64, 2);
  EXPECT_LT(error_64, error_4 + 1e-9);
}

TEST(RenderImageTest, GouraudRampIsLinearAcrossTheImage) {
  DisplayMesh mesh;
  AddQuad(
      1.5, [](double) { return 1.0; },
      [](const Vec3& p) {
        return Rgb{p.x + 2, p.y + 2, 1};
      },
      &mesh);
  const Image image = RenderImage(mesh, FrontCamera(100, 100, 4));
  for (uint32_t j = 0; j < 100; ++j) {
    for (uint32_t i = 0; i < 100; ++i) {
      // The box filter's mean of a linear function is its value at the pixel centre.
      const double world_x = -(i + 0.5 - 50) / 50;
      const double world_y = (50 - (j + 0.5)) / 50;
      ASSERT_NEAR(image.At(i, j).r, world_x + 2, 1e-9) << i << "," << j;
      ASSERT_NEAR(image.At(i, j).g, world_y + 2, 1e-9) << i << "," << j;
      ASSERT_NEAR(image.At(i, j).b, 1, 1e-12) << i << "," << j;
    }
  }
}

TEST(RenderImageTest, InterpolationIsPerspectiveCorrect) {
  // Plane z = 2 + x, radiance linear in world x: screen-linear shading would be wrong here.
  DisplayMesh mesh;
  AddQuad(
      1.5, [](double x) { return 2 + x; },
      [](const Vec3& p) {
        return Rgb{p.x + 2, 0, 0};
      },
      &mesh);
  const Image image = RenderImage(mesh, FrontCamera(100, 100, 1));
  int checked = 0;
  for (uint32_t j = 0; j < 100; ++j) {
    for (uint32_t i = 0; i < 100; ++i) {
      const double u = (i + 0.5 - 50) / 50, v = (50 - (j + 0.5)) / 50;
      // Ray (-u, v, 1) * t meets z = 2 + x at t = 2 / (1 + u).
      const double t = 2 / (1 + u);
      const double x = -u * t, y = v * t;
      if (std::fabs(x) > 1.45 || std::fabs(y) > 1.45) continue;
      ASSERT_NEAR(image.At(i, j).r, x + 2, 1e-9) << i << "," << j;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(RenderImageTest, ZBufferKeepsTheNearerTriangleInEitherOrder) {
  for (bool near_first : {true, false}) {
    DisplayMesh mesh;
    auto add_near = [&] {
      AddTriangle({-0.3, -0.3, 1}, {0.3, -0.3, 1}, {0, 0.3, 1}, Constant({1, 0, 0}), &mesh);
    };
    auto add_far = [&] {
      AddTriangle({-3, -3, 2}, {3, -3, 2}, {0, 3, 2}, Constant({0, 1, 0}), &mesh);
    };
    if (near_first) {
      add_near();
      add_far();
    } else {
      add_far();
      add_near();
    }
    const Image image = RenderImage(mesh, FrontCamera(100, 100, 4));
    EXPECT_EQ(image.At(50, 50), Rgb(1, 0, 0)) << near_first;
    EXPECT_EQ(image.At(50, 90), Rgb(0, 1, 0)) << near_first;
  }
}

TEST(RenderImageTest, ZBufferResolvesIntersectingTriangles) {
  // Two triangles crossing along x = 0 in depth: each is in front on one side.
  DisplayMesh mesh;
  AddTriangle({-1, -1, 1}, {1, -1, 3}, {0, 1, 2}, Constant({1, 0, 0}), &mesh);
  AddTriangle({-1, -1, 3}, {1, -1, 1}, {0, 1, 2}, Constant({0, 0, 1}), &mesh);
  const Image image = RenderImage(mesh, FrontCamera(100, 100, 1));
  // Image left is world +x, where the second triangle is nearer.
  EXPECT_EQ(image.At(40, 60), Rgb(0, 0, 1));
  EXPECT_EQ(image.At(60, 60), Rgb(1, 0, 0));
}

TEST(RenderImageTest, SharedEdgesLeaveNoCracks) {
  // A jittered 20 x 20 grid of triangles filling the view: every sample must be covered.
  const int cells = 20;
  auto vertex = [&](int i, int j) {
    const bool inner = i > 0 && i < cells && j > 0 && j < cells;
    const double jx = inner ? 0.3 * std::sin(i * 12.9898 + j * 78.233) : 0;
    const double jy = inner ? 0.3 * std::cos(i * 39.346 + j * 11.135) : 0;
    return Vec3{-1.2 + 2.4 * (i + jx) / cells, -1.2 + 2.4 * (j + jy) / cells, 1};
  };
  DisplayMesh mesh;
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      AddTriangle(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), Constant({1, 1, 1}), &mesh);
      AddTriangle(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1), Constant({1, 1, 1}), &mesh);
    }
  }
  const Image image = RenderImage(mesh, FrontCamera(97, 83, 9));
  for (const Rgb& p : image.pixels) ASSERT_NEAR(p.r, 1, 1e-12);
}

TEST(RenderImageTest, BothSidesAreDrawn) {
  DisplayMesh front, back;
  AddTriangle({-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0, 0.5, 1}, Constant({1, 1, 1}), &front);
  AddTriangle({-0.5, -0.5, 1}, {0, 0.5, 1}, {0.5, -0.5, 1}, Constant({1, 1, 1}), &back);
  const Camera camera = FrontCamera(64, 64, 4);
  const Image a = RenderImage(front, camera);
  EXPECT_GT(SumRed(a), 100);
  EXPECT_EQ(a.pixels, RenderImage(back, camera).pixels);
}

TEST(RenderImageTest, TrianglesBehindTheCameraAreClipped) {
  DisplayMesh mesh;
  // Crosses the eye plane: its front part projects to a band running off to infinity.
  AddTriangle({-1, -1, -5}, {-0.2, 0.6, 1}, {1, 0.3, 2}, Constant({1, 0, 0}), &mesh);
  // A floor wrapping around the camera, reaching behind it.
  AddTriangle({-100, -1, -1}, {100, -1, -1}, {0, -1, 100}, Constant({0, 1, 0}), &mesh);
  // Through the eye itself: seen edge-on, so it covers nothing, but must not produce NaNs.
  AddTriangle({0, 0, 0}, {1, 0, 1}, {0, 1, 1}, Constant({0, 0, 1}), &mesh);
  const Image image = RenderImage(mesh, FrontCamera(80, 60, 4));
  int red = 0, green = 0;
  for (const Rgb& p : image.pixels) {
    ASSERT_TRUE(p.IsFinite());
    ASSERT_LE(p.Max(), 1 + 1e-12);
    ASSERT_GE(p.Min(), 0);
    red += p.r == 1;
    green += p.g == 1;
  }
  EXPECT_GT(red, 50);
  EXPECT_GT(green, 50);
  EXPECT_EQ(image.At(79, 0), Rgb());          // above the horizon, right of the band: background
  EXPECT_EQ(image.At(40, 59), Rgb(0, 1, 0));  // floor right below the camera
}

TEST(RenderImageTest, EntirelyBehindTheCameraIsBlack) {
  DisplayMesh mesh;
  AddTriangle({-1, -1, -1}, {1, -1, -1}, {0, 1, -1}, Constant({1, 1, 1}), &mesh);
  const Image image = RenderImage(mesh, FrontCamera(32, 32, 4));
  for (const Rgb& p : image.pixels) ASSERT_EQ(p, Rgb());
}

TEST(RenderImageTest, BadTrianglesAreSkipped) {
  DisplayMesh mesh;
  AddTriangle({-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0, 0.5, 1}, Constant({1, 1, 1}), &mesh);
  mesh.triangles.push_back({0, 1, 99});  // index out of range
  mesh.positions.push_back({NAN, 0, 1});
  mesh.triangles.push_back({0, 1, 3});  // non-finite vertex
  mesh.positions.push_back({0, -0.9, 1});
  mesh.triangles.push_back({0, 1, 4});  // no radiance for vertex 4: black
  const Image image = RenderImage(mesh, FrontCamera(32, 32, 4));
  for (const Rgb& p : image.pixels) ASSERT_TRUE(p.IsFinite());
}

TEST(RenderImageTest, DeterministicAndSized) {
  DisplayMesh mesh;
  AddQuad(
      0.7, [](double x) { return 1.5 + 0.3 * x; },
      [](const Vec3& p) {
        return Rgb{p.x, p.y, p.z};
      },
      &mesh);
  const Camera camera = FrontCamera(33, 17, 5);
  const Image a = RenderImage(mesh, camera);
  const Image b = RenderImage(mesh, camera);
  EXPECT_EQ(a.width, 33u);
  EXPECT_EQ(a.height, 17u);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_TRUE(RenderImage(mesh, FrontCamera(0, 10, 4)).pixels.empty());
}

TEST(RenderImageTest, AutomaticCameraFramesTheMesh) {
  DisplayMesh mesh;
  AddQuad(
      10, [](double x) { return 50 + x; }, Constant({1, 1, 1}), &mesh);
  Camera camera;  // automatic by default
  camera.width = 64;
  camera.height = 48;
  const Image image = RenderImage(mesh, camera);
  EXPECT_GT(image.At(32, 24).r, 0.99);
  // The bounding sphere fits the view, so the corners stay background.
  EXPECT_EQ(image.At(0, 0), Rgb());
  EXPECT_EQ(image.At(63, 47), Rgb());
  EXPECT_FALSE(ResolveCamera(mesh, camera).automatic);
}

TEST(RenderImageTest, TenThousandTrianglesRenderQuickly) {
  // A 50 x 100 grid of quads (10k triangles) filling a 512 x 512, 4 spp image.
  DisplayMesh mesh;
  const int nx = 50, ny = 100;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      auto p = [&](int a, int b) {
        return Vec3{-1.2 + 2.4 * a / nx, -1.2 + 2.4 * b / ny, 1 + 0.1 * a / nx};
      };
      AddTriangle(p(i, j), p(i + 1, j), p(i + 1, j + 1), Constant({1, 0.5, 0.25}), &mesh);
      AddTriangle(p(i, j), p(i + 1, j + 1), p(i, j + 1), Constant({1, 0.5, 0.25}), &mesh);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const Image image = RenderImage(mesh, FrontCamera(512, 512, 4));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("seconds", std::to_string(seconds));
  std::printf("512x512, 4 spp, %zu triangles: %.3f s\n", mesh.triangles.size(), seconds);
  EXPECT_NEAR(image.At(256, 256).r, 1, 1e-12);
}

// Triangles are set up a chunk at a time: a depth tie is still won by the triangle drawn first,
// here one 70,000 triangles (more than a chunk) before its twin.
TEST(RenderImageTest, DepthTiesAcrossChunksKeepTheFirstTriangle) {
  DisplayMesh mesh;
  AddQuad(
      0.5, [](double) { return 1.0; }, Constant({1, 0, 0}), &mesh);
  for (int k = 0; k < 35000; ++k) {  // off to the side, behind the eye: clipped away
    AddQuad(
        0.1, [](double) { return -5.0; }, Constant({0, 0, 1}), &mesh);
  }
  AddQuad(
      0.5, [](double) { return 1.0; }, Constant({0, 1, 0}), &mesh);
  ASSERT_GT(mesh.triangles.size(), 70000u);
  const Image image = RenderImage(mesh, FrontCamera(100, 100, 4));
  EXPECT_EQ(image.At(50, 50), Rgb({1, 0, 0}));
  EXPECT_EQ(image.At(30, 70), Rgb({1, 0, 0}));
}

// An image whose subpixel strata exceed the 64 MB drawn at once is drawn a stratum at a time:
// the box filter of a linear ramp is still its value at each pixel centre, so every stratum was
// drawn, at its own offset, once.
TEST(RenderImageTest, LargeImagesDrawTheirStrataInTurn) {
  DisplayMesh mesh;
  AddQuad(
      1.5, [](double) { return 1.0; },
      [](const Vec3& p) {
        return Rgb{p.x + 2, p.y + 2, 1};
      },
      &mesh);
  const uint32_t size = 1500;  // 4 strata of 1500 x 1500 samples at 32 bytes: 288 MB
  const Image image = RenderImage(mesh, FrontCamera(size, size, 4));
  const double half = size / 2.0;
  for (uint32_t j = 0; j < size; j += 37) {
    for (uint32_t i = 0; i < size; i += 41) {
      ASSERT_NEAR(image.At(i, j).r, -(i + 0.5 - half) / half + 2, 1e-9) << i << "," << j;
      ASSERT_NEAR(image.At(i, j).g, (half - (j + 0.5)) / half + 2, 1e-9) << i << "," << j;
    }
  }
}

TEST(RenderImageTest, BlackPatchesHideWhatIsBehindAndShowNothing) {
  DisplayMesh mesh;
  AddQuad(
      1.5, [](double) { return 2.0; }, Constant({1, 1, 1}), &mesh);  // patches 0 and 1
  AddQuad(
      0.2, [](double) { return 1.0; }, Constant({5, 5, 5}), &mesh);  // patches 2 and 3
  const Camera camera = FrontCamera(100, 100, 1);
  EXPECT_EQ(RenderImage(mesh, camera).At(50, 50), Rgb({5, 5, 5}));
  const Image masked = RenderImage(mesh, camera, {false, false, true, true});
  EXPECT_EQ(masked.At(50, 50), Rgb());
  EXPECT_EQ(masked.At(20, 20), Rgb({1, 1, 1}));
}

}  // namespace
}  // namespace radfarm
