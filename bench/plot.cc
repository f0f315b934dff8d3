#include "bench/plot.h"

#include <sys/wait.h>

#include <cstdio>
#include <sstream>

namespace radfarm::bench {
namespace {

// gnuplot string literal in single quotes: only the quote itself needs escaping (doubled).
std::string Quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string Script(const PlotSpec& spec) {
  std::ostringstream s;
  s.precision(9);
  s << "set terminal pngcairo size " << 100 + 600 * spec.panels.size() << ",680 font ',11'\n"
    << "set output " << Quoted(spec.png_path) << "\n"
    << "set xlabel " << Quoted(spec.x_label) << "\n"
    << "set logscale xy\nset grid xtics ytics mxtics mytics\nset key below\n";
  // Inline data blocks keep the script self-contained.
  for (size_t p = 0; p < spec.panels.size(); ++p) {
    for (size_t i = 0; i < spec.panels[p].series.size(); ++i) {
      s << "$d" << p << "_" << i << " << EOD\n";
      for (const auto& [x, y] : spec.panels[p].series[i].points) s << x << " " << y << "\n";
      s << "EOD\n";
    }
  }
  s << "set multiplot layout 1," << spec.panels.size() << " title " << Quoted(spec.title) << "\n";
  for (size_t p = 0; p < spec.panels.size(); ++p) {
    const PlotPanel& panel = spec.panels[p];
    s << "set title " << Quoted(panel.title) << "\nset ylabel " << Quoted(panel.y_label)
      << "\nplot ";
    for (size_t i = 0; i < panel.series.size(); ++i) {
      const PlotSeries& series = panel.series[i];
      s << (i ? ", \\\n     " : "") << "$d" << p << "_" << i << " using 1:2 with "
        << (series.line ? "linespoints lw 2 ps 1.2" : "points ps 2.2") << " pt "
        << (series.point_type ? series.point_type
            : series.line     ? 7
                              : 9)
        << " lc " << (series.color ? series.color : int(i) + 1) << " title "
        << Quoted(series.title);
    }
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace

std::string WritePlot(const PlotSpec& spec) {
  FILE* gnuplot = popen("gnuplot", "w");
  if (!gnuplot) return "cannot start gnuplot";
  const std::string script = Script(spec);
  const bool written = std::fwrite(script.data(), 1, script.size(), gnuplot) == script.size();
  const int status = pclose(gnuplot);
  if (!written) return "cannot write to gnuplot";
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return "gnuplot failed (is gnuplot installed?) writing " + spec.png_path;
  }
  return "";
}

}  // namespace radfarm::bench
