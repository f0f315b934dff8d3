#include "bench/sweep_plot.h"

#include <cstdio>

namespace radfarm::bench {
namespace {

// gnuplot's default palette: grid purple, random green, Sobol blue, the seed's method red.
constexpr int kGridColor = 1, kSobolColor = 3, kSeedColor = 7;
constexpr int kSquare = 5, kTriangle = 9;

PlotPanel Panel(const SceneSweep& sweep, const SweepConfig& config, const SeedWorkload* seed,
                double SweepPoint::*error, const std::string& title) {
  PlotPanel panel;
  panel.title = title;
  panel.y_label = "RMS relative patch error";
  for (SamplerKind kind : {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol}) {
    PlotSeries series;
    series.title = std::string(SamplerName(kind));
    if (kind == SamplerKind::kGrid) {
      char text[64];
      std::snprintf(text, sizeof text, "grid %g°, %u shooters per round", config.grid_step_degrees,
                    config.grid_shooters_per_round);
      series.title = text;
    }
    for (const SweepPoint& p : sweep.points) {
      if (p.settings.sampler == kind) series.points.push_back({p.seconds, p.*error});
    }
    panel.series.push_back(series);
  }
  if (!sweep.grid_converged.empty()) {
    PlotSeries converged{"grid run to the tolerance (", {}, false, kGridColor, kSquare};
    for (const SweepPoint& p : sweep.grid_converged) {
      char text[32];
      std::snprintf(text, sizeof text, "%s%g°", converged.points.empty() ? "" : ", ",
                    p.settings.grid_step_degrees);
      converged.title += text;
      converged.points.push_back({p.seconds, p.*error});
    }
    converged.title += ")";
    panel.series.push_back(converged);
  }
  if (seed) {
    panel.series.push_back({"seed method: grid 1°, 20 shots",
                            {{seed->seed.seconds, seed->seed.*error}},
                            false,
                            kSeedColor,
                            kTriangle});
    panel.series.push_back({"default sampler at the seed method's time",
                            {{seed->equal_time.point.seconds, seed->equal_time.point.*error}},
                            false,
                            kSobolColor,
                            kTriangle});
  }
  return panel;
}

}  // namespace

PlotSpec MakeSweepPlot(const SceneSweep& sweep, const SweepConfig& config, const SeedWorkload* seed,
                       const std::string& png_path) {
  PlotSpec spec;
  spec.png_path = png_path;
  spec.title = sweep.scene + " (" + std::to_string(sweep.patches) + " patches): error against time";
  spec.x_label =
      "wall time of Solve(), seconds (median of " + std::to_string(config.repetitions) + ")";
  spec.panels.push_back(Panel(
      sweep, config, seed, &SweepPoint::error,
      "all patches with Bref > 0 (" + std::to_string(sweep.reference.patches.all.size()) + ")"));
  spec.panels.push_back(Panel(sweep, config, seed, &SweepPoint::error_lit,
                              "lit patches: Bref >= 1% of the median (" +
                                  std::to_string(sweep.reference.patches.lit.size()) + ")"));
  return spec;
}

}  // namespace radfarm::bench
