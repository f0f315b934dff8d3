#include "output/image.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "output/clip_polygon.h"
#include "output/enclosure_camera.h"
#include "output/view_transform.h"

namespace radfarm {
namespace {

// Clip planes sit at twice the image's half-extent: triangles reaching far off-screen are cut, so
// pixel coordinates stay within a few image sizes and edge functions keep their precision.
constexpr double kGuardBand = 2.0;
// Near plane as a fraction of the scene's far extent. Depth is stored as 1/z in doubles, so a tiny
// near distance costs no depth precision; it only has to keep the perspective divide finite.
constexpr double kNearFraction = 1e-5;
// Screen triangles set up at once, and the bytes of subpixel strata drawn at once (RenderImage).
constexpr size_t kChunkTriangles = size_t{1} << 16;
constexpr size_t kStrataBytes = size_t{64} << 20;

struct ScreenVertex {
  double x = 0, y = 0;
  double inv_z = 0;     // 1 / depth: linear in screen space
  Rgb radiance_over_z;  // radiance / depth: linear in screen space (perspective-correct shading)
};

// Edge function of the directed edge a->b, >= 0 on the triangle's inner side. The endpoints are
// stored in a canonical order (lexicographically smaller first) with a sign, so the two triangles
// sharing an edge compute bit-identical magnitudes and no sample on the edge falls through a crack.
struct Edge {
  double ax = 0, ay = 0, dx = 0, dy = 0, sign = 1;

  static Edge Make(const ScreenVertex& a, const ScreenVertex& b) {
    const bool swap = (b.x < a.x) || (b.x == a.x && b.y < a.y);
    const ScreenVertex& p = swap ? b : a;
    const ScreenVertex& q = swap ? a : b;
    return {p.x, p.y, q.x - p.x, q.y - p.y, swap ? -1.0 : 1.0};
  }
  double Evaluate(double px, double py) const { return sign * (dx * (py - ay) - dy * (px - ax)); }
};

struct ScreenTriangle {
  ScreenVertex v[3];
  Edge edges[3];  // edges[i] is opposite v[i], so edges[i] / area is v[i]'s barycentric weight
  double inv_area = 0;
  double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
};

uint32_t GridSize(uint32_t samples_per_pixel) {
  uint32_t n = 1;
  while (static_cast<uint64_t>(n) * n < samples_per_pixel) ++n;
  return n;
}

void AddTriangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c,
                 std::vector<ScreenTriangle>* out) {
  ScreenTriangle t;
  t.v[0] = a;
  t.v[1] = b;
  t.v[2] = c;
  t.edges[0] = Edge::Make(b, c);
  t.edges[1] = Edge::Make(c, a);
  t.edges[2] = Edge::Make(a, b);
  const double area = t.edges[2].Evaluate(c.x, c.y);
  if (!(area != 0) || !std::isfinite(area)) return;  // degenerate or edge-on: covers nothing
  if (area < 0) {
    // Both sides are drawn: flip clockwise triangles instead of culling them.
    for (Edge& e : t.edges) e.sign = -e.sign;
  }
  t.inv_area = 1 / std::fabs(area);
  t.min_x = std::min({a.x, b.x, c.x});
  t.max_x = std::max({a.x, b.x, c.x});
  t.min_y = std::min({a.y, b.y, c.y});
  t.max_y = std::max({a.y, b.y, c.y});
  out->push_back(t);
}

// The view's clip planes: the near plane and the guard band.
struct ClipPlanes {
  ClipPlane planes[5];
};

ClipPlanes MakeClipPlanes(const DisplayMesh& mesh, const ViewTransform& view) {
  const Bounds3 bounds = MeshBounds(mesh);
  const double far = Length(bounds.Centre() - view.eye) + 0.5 * bounds.Diagonal();
  const double near = (far > 0 && std::isfinite(far)) ? kNearFraction * far : kNearFraction;
  const double gx = kGuardBand * view.centre_x / view.focal_pixels;
  const double gy = kGuardBand * view.centre_y / view.focal_pixels;
  return {
      {{{0, 0, 1}, -near}, {{-1, 0, gx}, 0}, {{1, 0, gx}, 0}, {{0, -1, gy}, 0}, {{0, 1, gy}, 0}}};
}

// Whether the eye sees the triangle's back: its corners run clockwise seen from the eye.
bool FacesAway(const DisplayMesh& mesh, const std::array<uint32_t, 3>& v, const Vec3& eye) {
  const Vec3& a = mesh.positions[v[0]];
  return Dot(Cross(mesh.positions[v[1]] - a, mesh.positions[v[2]] - a), eye - a) <= 0;
}

// Screen triangles of mesh.triangles[first, last), in mesh order, into `triangles` (cleared);
// triangles of the patches `black_patch` marks get radiance 0.
void SetUpTriangles(const DisplayMesh& mesh, const ViewTransform& view, const ClipPlanes& clip,
                    const std::vector<bool>& black_patch, size_t first, size_t last,
                    std::vector<ScreenTriangle>* out) {
  std::vector<ScreenTriangle>& triangles = *out;
  triangles.clear();
  const size_t vertex_count = mesh.positions.size();
  for (size_t t = first; t < last; ++t) {
    const auto& indices = mesh.triangles[t];
    if (indices[0] >= vertex_count || indices[1] >= vertex_count || indices[2] >= vertex_count) {
      continue;
    }
    const uint32_t patch = t < mesh.triangle_patch.size() ? mesh.triangle_patch[t] : ~0u;
    if (patch < mesh.patch_front_only.size() && mesh.patch_front_only[patch] &&
        FacesAway(mesh, indices, view.eye)) {
      continue;  // the other side of a two-sided surface is drawn here
    }
    const bool black = patch < black_patch.size() && black_patch[patch];
    ClipPolygon polygon;
    polygon.count = 3;
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      const uint32_t index = indices[k];
      polygon.vertices[k].position = view.ToCamera(mesh.positions[index]);
      polygon.vertices[k].radiance =
          !black && index < mesh.radiance.size() ? mesh.radiance[index] : Rgb{};
      finite = finite && IsFinite(polygon.vertices[k].position);
    }
    if (!finite) continue;
    for (const ClipPlane& plane : clip.planes) {
      bool outside = false;
      for (int k = 0; k < polygon.count; ++k) {
        outside = outside || plane.Distance(polygon.vertices[k].position) < 0;
      }
      if (outside) ClipAgainstPlane(plane, &polygon);
      if (polygon.count < 3) break;
    }
    if (polygon.count < 3) continue;

    ScreenVertex projected[kMaxClipVertices];
    for (int k = 0; k < polygon.count; ++k) {
      const ClipVertex& v = polygon.vertices[k];
      projected[k].x = view.PixelX(v.position);
      projected[k].y = view.PixelY(v.position);
      projected[k].inv_z = 1 / v.position.z;
      projected[k].radiance_over_z = v.radiance * projected[k].inv_z;
    }
    // The clipped polygon is convex: a fan covers it.
    for (int k = 1; k + 1 < polygon.count; ++k) {
      AddTriangle(projected[0], projected[k], projected[k + 1], &triangles);
    }
  }
}

// Pixel range [first, last] whose sample at offset `offset` lies within [lo, hi], clamped to the
// image; empty when first > last.
void SampleRange(double lo, double hi, double offset, uint32_t size, int64_t* first,
                 int64_t* last) {
  const double a = std::max(0.0, std::ceil(lo - offset));
  const double b = std::min(static_cast<double>(size) - 1, std::floor(hi - offset));
  *first = static_cast<int64_t>(a);
  *last = b < a ? *first - 1 : static_cast<int64_t>(b);
}

// One subpixel sample per pixel at (x + ox, y + oy), z-buffered on 1/z (larger is nearer; a tie
// keeps the triangle drawn first, so the result does not depend on anything but mesh order), over
// what earlier triangles left in `depth` and `colour`.
void RasterisePass(const std::vector<ScreenTriangle>& triangles, double ox, double oy,
                   uint32_t width, uint32_t height, std::vector<double>* depth,
                   std::vector<Rgb>* colour) {
  for (const ScreenTriangle& t : triangles) {
    int64_t x0, x1, y0, y1;
    SampleRange(t.min_x, t.max_x, ox, width, &x0, &x1);
    SampleRange(t.min_y, t.max_y, oy, height, &y0, &y1);
    for (int64_t y = y0; y <= y1; ++y) {
      const double sy = static_cast<double>(y) + oy;
      const size_t row = static_cast<size_t>(y) * width;
      for (int64_t x = x0; x <= x1; ++x) {
        const double sx = static_cast<double>(x) + ox;
        const double e0 = t.edges[0].Evaluate(sx, sy);
        const double e1 = t.edges[1].Evaluate(sx, sy);
        const double e2 = t.edges[2].Evaluate(sx, sy);
        if (e0 < 0 || e1 < 0 || e2 < 0) continue;
        const double b0 = e0 * t.inv_area, b1 = e1 * t.inv_area, b2 = e2 * t.inv_area;
        const double inv_z = b0 * t.v[0].inv_z + b1 * t.v[1].inv_z + b2 * t.v[2].inv_z;
        const size_t i = row + static_cast<size_t>(x);
        if (!(inv_z > (*depth)[i])) continue;
        (*depth)[i] = inv_z;
        (*colour)[i] = (t.v[0].radiance_over_z * b0 + t.v[1].radiance_over_z * b1 +
                        t.v[2].radiance_over_z * b2) /
                       inv_z;
      }
    }
  }
}

}  // namespace

Bounds3 MeshBounds(const DisplayMesh& mesh) {
  Bounds3 bounds;
  for (const Vec3& p : mesh.positions) {
    if (IsFinite(p)) bounds.Extend(p);
  }
  return bounds;
}

Camera ResolveCamera(const DisplayMesh& mesh, const Camera& camera) {
  if (!camera.automatic) return camera;
  const Bounds3 bounds = MeshBounds(mesh);
  std::optional<Camera> inside = InsideCamera(mesh, bounds, camera);
  return inside ? *inside : AutoCamera(bounds, camera);
}

Image RenderImage(const DisplayMesh& mesh, const Camera& camera_in,
                  const std::vector<bool>& black_patch, ThreadPool* pool) {
  const Camera camera = ResolveCamera(mesh, camera_in);
  Image image;
  image.width = camera.width;
  image.height = camera.height;
  const size_t pixel_count = static_cast<size_t>(camera.width) * camera.height;
  image.pixels.assign(pixel_count, Rgb{});
  if (pixel_count == 0 || mesh.triangles.empty()) return image;

  const ViewTransform view = MakeViewTransform(camera);
  const ClipPlanes clip = MakeClipPlanes(mesh, view);
  // Memory stays independent of the mesh: triangles are set up a chunk at a time, and each chunk
  // is drawn into as many subpixel strata as kStrataBytes holds at once (all of them at the
  // default 4 samples of 512 x 512 pixels; a group at a time, each setting the chunks up again,
  // beyond). Every stratum still sees the triangles in mesh order, and strata are summed in order.
  const uint32_t n = GridSize(camera.samples_per_pixel);
  const size_t strata = static_cast<size_t>(n) * n;
  const size_t stratum_bytes = pixel_count * (sizeof(double) + sizeof(Rgb));
  const size_t group = std::clamp<size_t>(kStrataBytes / stratum_bytes, 1, strata);
  std::vector<std::vector<double>> depth(group);
  std::vector<std::vector<Rgb>> colour(group);
  std::vector<ScreenTriangle> triangles;
  triangles.reserve(std::min(kChunkTriangles, mesh.triangles.size()));
  for (size_t first_stratum = 0; first_stratum < strata; first_stratum += group) {
    const size_t count = std::min(group, strata - first_stratum);
    for (size_t g = 0; g < count; ++g) {
      depth[g].assign(pixel_count, 0.0);
      colour[g].assign(pixel_count, Rgb{});
    }
    for (size_t first = 0; first < mesh.triangles.size(); first += kChunkTriangles) {
      const size_t last = std::min(mesh.triangles.size(), first + kChunkTriangles);
      SetUpTriangles(mesh, view, clip, black_patch, first, last, &triangles);
      // Each stratum into buffers of its own: in any order, on any thread.
      ParallelForOrInline(pool, count, [&](unsigned, size_t g) {
        const size_t stratum = first_stratum + g;
        const double ox = (stratum % n + 0.5) / n, oy = (stratum / n + 0.5) / n;
        RasterisePass(triangles, ox, oy, camera.width, camera.height, &depth[g], &colour[g]);
      });
    }
    for (size_t g = 0; g < count; ++g) {
      for (size_t i = 0; i < pixel_count; ++i) image.pixels[i] += colour[g][i];
    }
  }
  const double weight = 1.0 / (static_cast<double>(n) * n);
  for (Rgb& p : image.pixels) p = p * weight;
  return image;
}

}  // namespace radfarm
