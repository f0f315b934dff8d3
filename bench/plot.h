// Error-against-time plots: a gnuplot script is generated and piped to a gnuplot child process,
// which writes the PNG (Debian's gnuplot-nox has the pngcairo terminal). Log-log, one panel per
// error measure, side by side.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace radfarm::bench {

struct PlotSeries {
  std::string title;
  std::vector<std::pair<double, double>> points;  // (x, y)
  bool line = true;                               // false: points only
  int color = 0;                                  // gnuplot line colour index (0: by position)
  int point_type = 0;  // gnuplot point type (0: filled circle for lines, triangle for points)
};

struct PlotPanel {
  std::string title;
  std::string y_label;
  std::vector<PlotSeries> series;
};

struct PlotSpec {
  std::string png_path;
  std::string title;
  std::string x_label;
  std::vector<PlotPanel> panels;
};

// Writes the plot. Returns an empty string on success, else what went wrong.
std::string WritePlot(const PlotSpec& spec);

}  // namespace radfarm::bench
