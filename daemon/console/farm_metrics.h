// FarmMetricsOf: the figures of /metrics from what the status page shows (the control socket's
// job and agent objects, docs/CONTROL.md) and the master's counters. Pure: tested alone.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>

#include "base/latency_histogram.h"
#include "daemon/console/web/metrics_text.h"
#include "daemon/jobs/batch_totals.h"

namespace radfarm::daemon {

// `jobs`, `agents`: arrays of job and agent objects. An agent is stale when its "stale" is true,
// else busy when it holds leases, else idle.
web::FarmMetrics FarmMetricsOf(const nlohmann::json& jobs, const nlohmann::json& agents,
                               const BatchTotals& batches,
                               const LatencyHistogram& checkpoint_latency,
                               size_t store_queue_depth);

}  // namespace radfarm::daemon
