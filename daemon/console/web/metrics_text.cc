#include "daemon/console/web/metrics_text.h"

#include <charconv>
#include <cmath>
#include <string_view>

namespace radfarm::web {
namespace {

std::string Number(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  char text[64];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return ec == std::errc() ? std::string(text, end) : "NaN";
}

// Label values escape backslash, double quote and newline (the format's only escapes).
std::string Escaped(std::string_view value) {
  std::string out;
  for (char c : value) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '"')
      out += "\\\"";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

class Exposition {
 public:
  void Family(std::string_view name, std::string_view type, std::string_view help) {
    text_ += "# HELP ";
    text_ += name;
    text_ += ' ';
    text_ += help;
    text_ += "\n# TYPE ";
    text_ += name;
    text_ += ' ';
    text_ += type;
    text_ += '\n';
  }
  void Sample(std::string_view name, double value, std::string_view label = {},
              std::string_view label_value = {}) {
    text_ += name;
    if (!label.empty()) {
      text_ += '{';
      text_ += label;
      text_ += "=\"";
      text_ += Escaped(label_value);
      text_ += "\"}";
    }
    text_ += ' ';
    text_ += Number(value);
    text_ += '\n';
  }
  void Labelled(std::string_view name, std::string_view type, std::string_view help,
                std::string_view label, const std::map<std::string, uint64_t>& values) {
    Family(name, type, help);
    for (const auto& [key, value] : values) Sample(name, double(value), label, key);
  }
  std::string Take() { return std::move(text_); }

 private:
  std::string text_;
};

}  // namespace

std::string FormatMetrics(const FarmMetrics& m) {
  Exposition e;
  e.Labelled("radfarm_jobs", "gauge", "Jobs in the store by state.", "state", m.jobs_by_state);
  e.Labelled("radfarm_agents", "gauge",
             "Authenticated agents: busy (holding leases), idle, or stale (silent).", "state",
             m.agents_by_state);
  e.Family("radfarm_rays_per_second", "gauge", "Rays per second over the running jobs.");
  e.Sample("radfarm_rays_per_second", m.rays_per_second);
  e.Family("radfarm_rays_total", "counter", "Rays traced for every job in the store.");
  e.Sample("radfarm_rays_total", double(m.rays_total));
  e.Family("radfarm_batches_issued_total", "counter",
           "Batch leases handed to agents since the master started.");
  e.Sample("radfarm_batches_issued_total", double(m.batches_issued));
  e.Family("radfarm_batches_reissued_total", "counter",
           "Batches leased again: overdue (a copy to a second agent) or requeued (after a lost, "
           "returned or revoked lease).");
  e.Sample("radfarm_batches_reissued_total", double(m.batches_reissued_overdue), "why", "overdue");
  e.Sample("radfarm_batches_reissued_total", double(m.batches_reissued_requeued), "why",
           "requeued");
  e.Family("radfarm_leases_preempted_total", "counter",
           "Live leases taken back from agents for a higher-priority job's batches.");
  e.Sample("radfarm_leases_preempted_total", double(m.leases_preempted));
  e.Family("radfarm_batch_results_accepted_total", "counter",
           "Batch results accepted (the first valid result of each batch).");
  e.Sample("radfarm_batch_results_accepted_total", double(m.results_accepted));
  e.Family("radfarm_batches_verified_total", "counter",
           "Accepted batch results computed again by the master and compared bit for bit.");
  e.Sample("radfarm_batches_verified_total", double(m.batches_verified));
  e.Family("radfarm_batch_verification_mismatches_total", "counter",
           "Verified batch results whose bits differed from the master's (the agent was "
           "blocklisted for the job and its results computed again).");
  e.Sample("radfarm_batch_verification_mismatches_total", double(m.verify_mismatches));
  e.Labelled("radfarm_batch_results_rejected_total", "counter",
             "Batch results rejected as the agent's fault, by reason.", "reason",
             m.results_rejected);
  e.Labelled("radfarm_batch_results_dropped_total", "counter",
             "Batch results dropped as late or repeated, by reason.", "reason", m.results_dropped);
  const char* kLatency = "radfarm_checkpoint_seconds";
  e.Family(kLatency, "histogram",
           "Time from a round's checkpoint being queued on the store thread to its commit.");
  const LatencyHistogram& h = m.checkpoint_seconds;
  const std::string bucket = std::string(kLatency) + "_bucket";
  for (size_t i = 0; i < LatencyHistogram::kBounds.size(); ++i) {
    e.Sample(bucket, double(h.CountAtMost(i)), "le", Number(LatencyHistogram::kBounds[i]));
  }
  e.Sample(bucket, double(h.count()), "le", "+Inf");
  e.Sample(std::string(kLatency) + "_sum", h.sum());
  e.Sample(std::string(kLatency) + "_count", double(h.count()));
  e.Family("radfarm_store_queue_depth", "gauge",
           "Store operations (SQLite transactions) queued, not yet started.");
  e.Sample("radfarm_store_queue_depth", double(m.store_queue_depth));
  e.Family("radfarm_round_results_kept_total", "counter",
           "Accepted batch results written to the store for a restart of the master.");
  e.Sample("radfarm_round_results_kept_total", double(m.round_results_kept));
  e.Family("radfarm_round_result_writes_total", "counter",
           "Store transactions that wrote them (results are grouped while one is running).");
  e.Sample("radfarm_round_result_writes_total", double(m.round_result_writes));
  e.Family("radfarm_batches_restored_total", "counter",
           "Batches whose stored result a restarted master folded in instead of leasing them.");
  e.Sample("radfarm_batches_restored_total", double(m.batches_restored));
  e.Family("radfarm_gather_ahead_batches_total", "counter",
           "Final-gather batches agents computed while the shooting rounds ran, accepted when the "
           "gather round started.");
  e.Sample("radfarm_gather_ahead_batches_total", double(m.gather_ahead_batches));
  return e.Take();
}

}  // namespace radfarm::web
