#include "output/illuminance_image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/atomic_file.h"
#include "output/png_writer.h"

namespace radfarm {
namespace {

constexpr std::array<uint8_t, 3> kBlack{0, 0, 0};
constexpr std::array<uint8_t, 3> kNoPoint{220, 220, 220};
constexpr uint32_t kMargin = 8;
constexpr uint32_t kPanelSide = 480;  // a panel's longer side, about, in pixels
constexpr uint32_t kBarHeight = 14;
constexpr int kTextScale = 2;
constexpr int kTicks = 5;

}  // namespace

double ColourScaleTop(double max) {
  if (!(max > 0) || !std::isfinite(max)) return 1;
  const double power = std::pow(10.0, std::floor(std::log10(max)));
  for (const double step : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (step * power >= max) return step * power;
  }
  return 10 * power;
}

std::array<uint8_t, 3> FalseColour(double lux, double top) {
  static constexpr std::array<std::array<double, 3>, 6> kStops = {{{30, 20, 110},
                                                                   {30, 110, 230},
                                                                   {30, 200, 200},
                                                                   {90, 200, 60},
                                                                   {250, 210, 40},
                                                                   {200, 30, 20}}};
  const double t = std::clamp(top > 0 ? lux / top : 0.0, 0.0, 1.0) * (kStops.size() - 1);
  const size_t k = std::min(size_t(t), kStops.size() - 2);
  const double f = t - double(k);
  std::array<uint8_t, 3> out;
  for (int c = 0; c < 3; ++c) {
    out[c] = uint8_t(std::lround(kStops[k][c] + (kStops[k + 1][c] - kStops[k][c]) * f));
  }
  return out;
}

std::string TickLabel(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  if (std::string(text).find('e') != std::string::npos && std::fabs(value) < 1e7) {
    std::snprintf(text, sizeof text, "%.0f", value);
  }
  return text;
}

Rgb8Image IlluminanceImage(const PlaneIlluminance& plane) {
  const IlluminanceGrid& grid = plane.grid;
  const uint32_t panels = std::max<uint32_t>(1, uint32_t(grid.levels.size()));
  const uint32_t cell =
      std::clamp<uint32_t>(kPanelSide / std::max({grid.columns, grid.rows, 1u}), 1, 32);
  const uint32_t panel_width = grid.columns * cell, panel_height = grid.rows * cell;
  const double top = ColourScaleTop(SummariseLux(plane.lux).max);
  const uint32_t text_height = kGlyphHeight * kTextScale;
  const std::string unit = "lx";
  const uint32_t bar_width = std::max<uint32_t>(
      200, std::min<uint32_t>(panels * panel_width + (panels - 1) * kMargin, 640));

  Rgb8Image image;
  image.width = std::max(panels * panel_width + (panels - 1) * kMargin,
                         bar_width + TextWidth(TickLabel(top), kTextScale) / 2 + kMargin +
                             TextWidth(unit, kTextScale)) +
                2 * kMargin;
  image.height = panel_height + 3 * kMargin + kBarHeight + 4 + text_height + kMargin;
  image.rgb.assign(size_t(image.width) * image.height * 3, 255);
  for (uint32_t p = 0; p < panels; ++p) {
    image.Fill(kMargin + p * (panel_width + kMargin), kMargin, panel_width, panel_height, kNoPoint);
  }
  for (size_t i = 0; i < grid.cells.size(); ++i) {
    const IlluminanceGrid::Cell& c = grid.cells[i];
    image.Fill(kMargin + c.level * (panel_width + kMargin) + c.column * cell,
               kMargin + c.row * cell, cell, cell, FalseColour(plane.lux[i], top));
  }

  // The legend: the bar, its ticks and their values, the unit after the last.
  const uint32_t bar_y = panel_height + 3 * kMargin;
  for (uint32_t x = 0; x < bar_width; ++x) {
    image.Fill(kMargin + x, bar_y, 1, kBarHeight, FalseColour(top * (x + 0.5) / bar_width, top));
  }
  const uint32_t label_y = bar_y + kBarHeight + 4;
  for (int k = 0; k < kTicks; ++k) {
    const uint32_t x = kMargin + uint32_t(k) * (bar_width - 1) / (kTicks - 1);
    image.Fill(x, bar_y + kBarHeight, 1, 3, kBlack);
    const std::string label = TickLabel(top * k / (kTicks - 1));
    const uint32_t width = TextWidth(label, kTextScale);
    const uint32_t left = k == 0 ? x : x - std::min(x, width / 2);
    DrawText(&image, left, label_y, label, kTextScale, kBlack);
  }
  DrawText(&image, kMargin + bar_width + TextWidth(TickLabel(top), kTextScale) / 2 + kMargin,
           label_y, unit, kTextScale, kBlack);
  return image;
}

Status WriteIlluminancePng(const std::string& path, const PlaneIlluminance& plane) {
  const Rgb8Image image = IlluminanceImage(plane);
  Result<std::string> encoded = EncodeRgb8Png(image.width, image.height, image.rgb);
  if (!encoded) return Error{path + ": " + encoded.error()};
  return WriteFileAtomically(path, *encoded);
}

}  // namespace radfarm
