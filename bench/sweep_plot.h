// The error-against-time plot of one scene's sweep: one panel per error measure, one line per
// sampler, and on the seed room the seed paper's workload and the default sampler at its time.
#pragma once

#include <string>

#include "bench/plot.h"
#include "bench/seed_workload.h"
#include "bench/sweep.h"

namespace radfarm::bench {

// `seed` may be null (no seed-workload markers).
PlotSpec MakeSweepPlot(const SceneSweep& sweep, const SweepConfig& config, const SeedWorkload* seed,
                       const std::string& png_path);

}  // namespace radfarm::bench
