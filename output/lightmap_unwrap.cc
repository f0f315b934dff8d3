#include "output/lightmap_unwrap.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "output/chart_packer.h"
#include "output/lightmap_charts.h"
#include "output/lightmap_writer.h"

namespace radfarm {
namespace {

constexpr double kTexelStep = 1.03;  // coarser texels tried when the charts do not fit
constexpr int kMaxTexelSteps = 400;  // 1.03^400: from a texel too fine to one that always fits

// One object's charts and their extents in its charts' planes.
struct ObjectCharts {
  std::vector<uint32_t> triangles;  // into the unwrapped list
  LightmapCharts charts;
  std::vector<FlatPoint> lo, hi;  // by chart
  double area = 0;                // scene units squared
};

ObjectCharts Chart(const std::vector<LightmapTriangle>& all, std::vector<uint32_t> triangles) {
  ObjectCharts out;
  std::vector<std::array<Vec3, 3>> positions;
  for (const uint32_t t : triangles) {
    positions.push_back(all[t].position);
    const auto& p = all[t].position;
    out.area += 0.5 * Length(Cross(p[1] - p[0], p[2] - p[0]));
  }
  out.triangles = std::move(triangles);
  out.charts = MakeLightmapCharts(positions);
  out.lo.assign(out.charts.count, {INFINITY, INFINITY});
  out.hi.assign(out.charts.count, {-INFINITY, -INFINITY});
  for (size_t i = 0; i < out.charts.chart.size(); ++i) {
    const uint32_t c = out.charts.chart[i];
    for (const FlatPoint& f : out.charts.flat[i]) {
      for (int a = 0; a < 2; ++a) {
        out.lo[c][a] = std::min(out.lo[c][a], f[a]);
        out.hi[c][a] = std::max(out.hi[c][a], f[a]);
      }
    }
  }
  // Charts lying down pack tighter: the skyline packer places them by height.
  std::vector<bool> tall(out.charts.count);
  for (uint32_t c = 0; c < out.charts.count; ++c) {
    tall[c] = out.hi[c][1] - out.lo[c][1] > out.hi[c][0] - out.lo[c][0];
    if (!tall[c]) continue;
    std::swap(out.lo[c][0], out.lo[c][1]);
    std::swap(out.hi[c][0], out.hi[c][1]);
  }
  for (size_t i = 0; i < out.charts.chart.size(); ++i) {
    if (!tall[out.charts.chart[i]]) continue;
    for (FlatPoint& f : out.charts.flat[i]) std::swap(f[0], f[1]);
  }
  return out;
}

// Each chart's rectangle at `texel`: its extent in texels, rounded up, plus the gutters.
std::vector<PackSize> Sizes(const ObjectCharts& o, double texel) {
  std::vector<PackSize> out;
  for (uint32_t c = 0; c < o.charts.count; ++c) {
    const auto side = [&](int a) {
      const double texels = std::ceil((o.hi[c][a] - o.lo[c][a]) / texel);
      return uint32_t(std::clamp(texels, 1.0, double(kMaxLightmapSize))) + 2 * kChartGutter;
    };
    out.push_back({side(0), side(1)});
  }
  return out;
}

uint64_t GutterTexels(const std::vector<PackSize>& sizes) {
  uint64_t out = 0;
  for (const PackSize& s : sizes) {
    out += uint64_t(s.width) * s.height -
           uint64_t(s.width - 2 * kChartGutter) * (s.height - 2 * kChartGutter);
  }
  return out;
}

// The finest texel, from `texel` up, at which the charts fit a square of `side`.
std::optional<std::pair<double, PackedSquare>> FitInto(const ObjectCharts& o, double texel,
                                                       uint32_t side) {
  for (int step = 0; step < kMaxTexelSteps; ++step, texel *= kTexelStep) {
    std::optional<PackedSquare> packed = PackInto(Sizes(o, texel), side);
    if (packed) return std::pair{texel, std::move(*packed)};
  }
  return std::nullopt;
}

std::optional<std::pair<double, PackedSquare>> Fit(const ObjectCharts& o, double texel,
                                                   uint32_t fixed_size) {
  // A texel below the one that fills the square exactly, gutters aside, cannot fit.
  const auto finest = [&](uint32_t side) { return std::sqrt(o.area) / side; };
  if (fixed_size > 0) return FitInto(o, finest(fixed_size), fixed_size);
  for (int step = 0; step < kMaxTexelSteps; ++step, texel *= kTexelStep) {
    std::optional<PackedSquare> packed = PackSmallest(Sizes(o, texel), kMaxLightmapSize);
    if (!packed) continue;
    // A small object fills the smallest lightmap with finer texels rather than leave it empty.
    if (packed->side < kMinLightmapSize)
      return FitInto(o, finest(kMinLightmapSize), kMinLightmapSize);
    return std::pair{texel, std::move(*packed)};
  }
  return std::nullopt;
}

}  // namespace

UnwrappedLightmaps UnwrapLightmaps(const std::vector<LightmapTriangle>& triangles,
                                   const std::vector<InputObject>& objects, double texel_size,
                                   uint32_t fixed_size, std::vector<std::string>* warnings) {
  UnwrappedLightmaps out;
  out.triangles = triangles;
  out.size.assign(objects.size(), 0);
  out.gutter_texels.assign(objects.size(), 0);
  std::vector<std::vector<uint32_t>> by_object(objects.size());
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    if (triangles[t].object < objects.size()) by_object[triangles[t].object].push_back(t);
  }
  for (uint32_t o = 0; o < objects.size(); ++o) {
    if (by_object[o].empty()) continue;
    const ObjectCharts charts = Chart(triangles, std::move(by_object[o]));
    if (!(charts.area > 0)) continue;  // nothing to light: the mesh drops such faces too
    const auto fit = Fit(charts, texel_size, fixed_size);
    if (!fit) {
      if (warnings != nullptr) {
        warnings->push_back(objects[o].name +
                            ": its lightmap charts do not fit a lightmap; it "
                            "has no lightmap");
      }
      continue;
    }
    const auto& [texel, packed] = *fit;
    out.size[o] = packed.side;
    out.gutter_texels[o] = GutterTexels(Sizes(charts, texel));
    for (size_t i = 0; i < charts.triangles.size(); ++i) {
      const uint32_t c = charts.charts.chart[i];
      LightmapTriangle& t = out.triangles[charts.triangles[i]];
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 2; ++a) {
          const double texels = (charts.charts.flat[i][k][a] - charts.lo[c][a]) / texel +
                                kChartGutter + packed.at[c][a];
          t.uv[k][a] = float(texels / packed.side);
        }
      }
    }
  }
  return out;
}

}  // namespace radfarm
