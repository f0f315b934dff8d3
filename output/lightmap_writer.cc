#include "output/lightmap_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <system_error>
#include <tuple>

#include "output/exr_writer.h"
#include "output/png_writer.h"
#include "output/tone_map.h"

namespace radfarm {
namespace {

constexpr int kSeamFitPasses = 16;

double UvArea(const std::array<Uv, 3>& t) {
  return 0.5 * std::abs(double(t[1][0] - t[0][0]) * double(t[2][1] - t[0][1]) -
                        double(t[1][1] - t[0][1]) * double(t[2][0] - t[0][0]));
}

double WorldArea(const std::array<Vec3, 3>& t) {
  return 0.5 * Length(Cross(t[1] - t[0], t[2] - t[0]));
}

// By input triangle: whether its front side (as the input faces) is the one to bake.
std::vector<bool> BakedSides(const DisplayMesh& mesh, const DisplayLightmapUvs& uvs,
                             size_t triangles) {
  std::vector<double> front(triangles, 0), back(triangles, 0);
  for (size_t d = 0; d < uvs.source.size(); ++d) {
    if (uvs.source[d] < 0) continue;
    const auto& t = mesh.triangles[d];
    const double light = Luminance(mesh.radiance[t[0]] + mesh.radiance[t[1]] + mesh.radiance[t[2]]);
    const double area =
        WorldArea({mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]});
    (uvs.front[d] ? front : back)[uvs.source[d]] += area * light;
  }
  std::vector<bool> out(triangles);
  for (size_t i = 0; i < triangles; ++i) out[i] = front[i] >= back[i];
  return out;
}

// 16 hex digits of the name's 64-bit FNV-1a: fixed, so a name always gives the same stem.
std::string NameHash(const std::string& name) {
  uint64_t h = 14695981039346656037ull;
  for (const char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  static const char kHex[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) out[size_t(i)] = kHex[h & 15];
  return out;
}

// Samples along every seam of one lightmap: display edges drawn twice (by position, bit for bit)
// at different UVs, about two a texel on each side, each side's own light at each point.
std::vector<UvRaster::Sample> SeamSamples(const DisplayMesh& mesh, const DisplayLightmapUvs& uvs,
                                          const std::vector<uint32_t>& drawn, uint32_t size) {
  using Key = std::tuple<double, double, double, double, double, double>;
  struct Side {
    uint32_t triangle;
    int corner;  // the edge from this corner to the next
    bool reversed;
  };
  std::map<Key, std::vector<Side>> edges;
  for (const uint32_t d : drawn) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = mesh.positions[mesh.triangles[d][k]];
      const Vec3& b = mesh.positions[mesh.triangles[d][(k + 1) % 3]];
      const bool reversed = std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z);
      const Vec3& lo = reversed ? b : a;
      const Vec3& hi = reversed ? a : b;
      edges[Key{lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}].push_back({d, k, reversed});
    }
  }
  std::vector<UvRaster::Sample> out;
  for (const auto& [key, sides] : edges) {
    if (sides.size() != 2) continue;
    std::array<std::array<Uv, 2>, 2> uv;
    std::array<std::array<Rgb, 2>, 2> light;
    for (int s = 0; s < 2; ++s) {
      const Side& side = sides[s];
      for (int e = 0; e < 2; ++e) {
        const int corner = (side.corner + (e != side.reversed ? 1 : 0)) % 3;
        uv[s][e] = uvs.uv[side.triangle][corner];
        light[s][e] = mesh.radiance[mesh.triangles[side.triangle][corner]];
      }
    }
    double texels = 0;
    for (int e = 0; e < 2; ++e) {
      texels = std::max({texels, std::abs(double(uv[0][e][0]) - uv[1][e][0]) * size,
                         std::abs(double(uv[0][e][1]) - uv[1][e][1]) * size});
    }
    if (texels < 0.5) continue;  // one place in UV: no seam
    for (int s = 0; s < 2; ++s) {
      const double length =
          std::hypot(double(uv[s][1][0]) - uv[s][0][0], double(uv[s][1][1]) - uv[s][0][1]) * size;
      const int count = std::clamp(int(std::ceil(2 * length)), 1, 1 << 16);
      for (int i = 0; i < count; ++i) {
        const double f = (i + 0.5) / count;
        out.push_back({Uv{float((1 - f) * uv[s][0][0] + f * uv[s][1][0]),
                          float((1 - f) * uv[s][0][1] + f * uv[s][1][1])},
                       light[s][0] * (1 - f) + light[s][1] * f});
      }
    }
  }
  return out;
}

}  // namespace

uint32_t LightmapSize(double world_area, double uv_area, double texel_size) {
  double side = std::sqrt(world_area / uv_area) / texel_size;
  if (!std::isfinite(side)) side = kMinLightmapSize;
  side = std::clamp(side, double(kMinLightmapSize), double(kMaxLightmapSize));
  return (static_cast<uint32_t>(std::ceil(side)) + 3) / 4 * 4;
}

std::vector<std::string> LightmapStems(const std::vector<InputObject>& objects) {
  std::vector<std::string> out;
  std::set<std::string> taken;  // lower-cased: case-insensitive file systems fold case
  for (size_t o = 0; o < objects.size(); ++o) {
    std::string stem = objects[o].name;
    for (char& c : stem) {
      const bool safe =
          std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
      if (!safe) c = '_';
    }
    if (stem.empty() || stem[0] == '.') stem = "object" + std::to_string(o) + stem;
    if (stem.size() > kMaxLightmapStem) {
      stem = stem.substr(0, kMaxLightmapStem - 17) + "_" + NameHash(objects[o].name);
    }
    const auto folded = [](std::string s) {
      for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
      return s;
    };
    std::string unique = stem;
    for (int n = 2; taken.count(folded(unique)) > 0; ++n) unique = stem + "_" + std::to_string(n);
    taken.insert(folded(unique));
    out.push_back(unique);
  }
  return out;
}

std::vector<Lightmap> WriteLightmaps(
    const std::string& dir, const DisplayMesh& mesh, const std::vector<InputObject>& objects,
    const DisplayLightmapUvs& uvs, const std::vector<LightmapTriangle>& triangles,
    const Camera& exposed, double texel_size, const std::vector<uint32_t>& sizes,
    std::vector<std::string>* warnings, std::vector<std::string>* failures) {
  std::vector<Lightmap> out;
  const std::vector<bool> baked = BakedSides(mesh, uvs, triangles.size());
  // By object: the input triangles' areas, for the resolution.
  std::vector<double> world_area(objects.size(), 0), uv_area(objects.size(), 0);
  for (const LightmapTriangle& t : triangles) {
    if (t.object >= objects.size()) continue;
    world_area[t.object] += WorldArea(t.position);
    uv_area[t.object] += UvArea(t.uv);
  }
  std::vector<std::vector<uint32_t>> drawn(objects.size());
  for (size_t d = 0; d < uvs.source.size(); ++d) {
    const int64_t s = uvs.source[d];
    if (s >= 0 && uvs.front[d] == baked[s]) drawn[triangles[s].object].push_back(uint32_t(d));
  }
  const std::vector<std::string> stems = LightmapStems(objects);
  namespace fs = std::filesystem;
  bool made_dir = false;
  for (uint32_t o = 0; o < objects.size(); ++o) {
    if (o >= uvs.object_has_uv.size() || !uvs.object_has_uv[o]) continue;
    if (!made_dir) {
      std::error_code ec;
      fs::create_directories(fs::path(dir) / "lightmaps", ec);
      if (ec) {
        failures->push_back(dir + "/lightmaps: cannot create: " + ec.message());
        return out;
      }
      made_dir = true;
    }
    Lightmap map;
    map.object = o;
    const uint32_t size = o < sizes.size() ? sizes[o] : 0;
    map.size = size > 0 ? size : LightmapSize(world_area[o], uv_area[o], texel_size);
    map.exr = "lightmaps/" + stems[o] + ".exr";
    map.png = "lightmaps/" + stems[o] + ".png";
    UvRaster raster(map.size, map.size);
    for (uint32_t d : drawn[o]) {
      const auto& t = mesh.triangles[d];
      raster.Draw(uvs.uv[d], {mesh.radiance[t[0]], mesh.radiance[t[1]], mesh.radiance[t[2]]});
    }
    raster.Extend(1.0);  // every texel bilinear filtering reads at the island's border
    raster.Fit(SeamSamples(mesh, uvs, drawn[o], map.size), kSeamFitPasses);
    raster.Dilate(kLightmapGutter);
    map.stats = raster.stats();
    const std::string& name = objects[o].name.empty() ? stems[o] : objects[o].name;
    if (warnings != nullptr && map.stats.overlapped * 100 > map.stats.covered) {
      warnings->push_back(name + ": its lightmap UVs (TEXCOORD_1) overlap: " +
                          std::to_string(map.stats.overlapped) + " of " +
                          std::to_string(map.stats.covered) +
                          " texels drawn twice (the first kept); unwrap it without overlaps");
    }
    // One object's failure leaves the others' lightmaps to be written.
    bool ok = true;
    for (const Status& s :
         {WriteExr((fs::path(dir) / map.exr).string(), raster.image()),
          WritePng((fs::path(dir) / map.png).string(), raster.image(), exposed)}) {
      if (!s.ok()) failures->push_back(s.error());
      ok = ok && s.ok();
    }
    if (ok) out.push_back(std::move(map));
  }
  if (warnings != nullptr && uvs.unplaced > 0) {
    warnings->push_back(std::to_string(uvs.unplaced) +
                        " display triangles lie on no input triangle with a lightmap UV; they "
                        "are missing from the lightmaps");
  }
  return out;
}

}  // namespace radfarm
