#include "bench/refine/reference_image.h"

#include <cmath>
#include <thread>

#include "bench/refine/element_points.h"
#include "core/counter_rng.h"
#include "core/direct_light.h"
#include "core/ray_caster.h"
#include "core/thread_pool.h"
#include "display/display_stage.h"

namespace radfarm::bench {
namespace {

// A copy of the display mesh with unshared vertices, each triangle's three carrying one value:
// rendered, it tells for every sample which patch it sees (value patch + 1; 0 where nothing) and
// where (the vertex positions, interpolated perspective-correctly).
DisplayMesh Unshared(const DisplayMesh& display) {
  DisplayMesh out;
  for (size_t t = 0; t < display.triangles.size(); ++t) {
    const uint32_t base = static_cast<uint32_t>(out.positions.size());
    for (uint32_t v : display.triangles[t]) out.positions.push_back(display.positions[v]);
    out.triangles.push_back({base, base + 1, base + 2});
    out.triangle_patch.push_back(display.triangle_patch[t]);
  }
  out.radiance.resize(out.positions.size());
  return out;
}

}  // namespace

std::vector<Rgb> BouncedRadiosity(const PatchScene& scene, const std::vector<Rgb>& radiosity) {
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster, kShadowRaysPerPoint);
  ThreadPool pool(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<Rgb> rest(radiosity);
  pool.ParallelFor(scene.patches.size(), [&](unsigned, size_t i) {
    const Patch& p = scene.patches[i];
    std::vector<SurfacePoint> points;
    AppendElementPoints(p, &points);
    Rgb sum;
    for (size_t k = 0; k < points.size(); ++k) {
      sum += direct.Irradiance(points[k].position, p.normal, HashWords(1, i, k));
    }
    rest[i] = rest[i] - p.reflectance * (sum / double(points.size()));
  });
  return rest;
}

Image RenderReferenceImage(const PatchMesh& mesh, const std::vector<Rgb>& rest,
                           const Camera& camera, Image* bounced_image) {
  const PatchScene& scene = mesh.patch_scene();
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster, kShadowRaysPerPoint);
  ThreadPool pool(std::max(1u, std::thread::hardware_concurrency()));

  // The bounced part, Gouraud-shaded.
  const DisplayMesh display = AveragedDisplay(mesh.display_topology(), scene, rest);

  // One sample per pixel of an image n times larger: the rasteriser's n x n subpixel samples.
  uint32_t n = 1;
  while (n * n < camera.samples_per_pixel) ++n;
  Camera fine = camera;
  fine.width *= n;
  fine.height *= n;
  fine.samples_per_pixel = 1;
  const Image smooth = RenderImage(display, fine);
  DisplayMesh unshared = Unshared(display);
  for (size_t v = 0; v < unshared.positions.size(); ++v) {
    unshared.radiance[v] = {double(unshared.triangle_patch[v / 3]) + 1, 0, 0};
  }
  const Image ids = RenderImage(unshared, fine);
  for (size_t v = 0; v < unshared.positions.size(); ++v) {
    const Vec3& q = unshared.positions[v];
    unshared.radiance[v] = {q.x, q.y, q.z};
  }
  const Image where = RenderImage(unshared, fine);

  std::vector<Rgb> samples(smooth.pixels);
  pool.ParallelFor(samples.size(), [&](unsigned, size_t s) {
    const double id = std::round(ids.pixels[s].r);
    if (id < 1) return;  // nothing seen
    const Patch& p = scene.patches[static_cast<size_t>(id) - 1];
    const Rgb& q = where.pixels[s];
    samples[s] += p.reflectance * direct.Irradiance({q.r, q.g, q.b}, p.normal, HashWords(2, s));
  });

  Image image;
  image.width = camera.width;
  image.height = camera.height;
  image.pixels.resize(size_t(image.width) * image.height);
  for (uint32_t y = 0; y < fine.height; ++y) {
    for (uint32_t x = 0; x < fine.width; ++x) {
      image.pixels[size_t(y / n) * image.width + x / n] += samples[size_t(y) * fine.width + x];
    }
  }
  for (Rgb& p : image.pixels) p = p / double(n * n);
  *bounced_image = RenderImage(display, camera);
  return image;
}

}  // namespace radfarm::bench
