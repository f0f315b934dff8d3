#include "daemon/console/web/metrics_text.h"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

namespace radfarm::web {
namespace {

FarmMetrics Example() {
  FarmMetrics m;
  m.jobs_by_state = {{"done", 2}, {"queued", 0}, {"running", 1}};
  m.agents_by_state = {{"busy", 3}, {"idle", 1}, {"stale", 0}};
  m.rays_per_second = 1234567.5;
  m.rays_total = 9200000;
  m.batches_issued = 500;
  m.batches_reissued_overdue = 4;
  m.batches_reissued_requeued = 7;
  m.leases_preempted = 6;
  m.results_accepted = 490;
  m.batches_verified = 12;
  m.verify_mismatches = 1;
  m.results_rejected = {{"invalid", 1}};
  m.results_dropped = {{"late", 3}};
  m.checkpoint_seconds.Record(0.004);
  m.checkpoint_seconds.Record(0.03);
  m.checkpoint_seconds.Record(20);
  m.store_queue_depth = 5;
  return m;
}

TEST(MetricsTextTest, EverySeriesHasHelpAndTypeAndTheExactValue) {
  const std::string text = FormatMetrics(Example());
  for (const char* line : {
           "# TYPE radfarm_jobs gauge",
           "radfarm_jobs{state=\"done\"} 2",
           "radfarm_jobs{state=\"queued\"} 0",
           "radfarm_agents{state=\"busy\"} 3",
           "radfarm_rays_per_second 1234567.5",
           "radfarm_rays_total 9200000",
           "# TYPE radfarm_batches_issued_total counter",
           "radfarm_batches_issued_total 500",
           "radfarm_batches_reissued_total{why=\"overdue\"} 4",
           "radfarm_batches_reissued_total{why=\"requeued\"} 7",
           "# TYPE radfarm_leases_preempted_total counter",
           "radfarm_leases_preempted_total 6",
           "radfarm_batch_results_accepted_total 490",
           "# TYPE radfarm_batches_verified_total counter",
           "radfarm_batches_verified_total 12",
           "radfarm_batch_verification_mismatches_total 1",
           "radfarm_batch_results_rejected_total{reason=\"invalid\"} 1",
           "radfarm_batch_results_dropped_total{reason=\"late\"} 3",
           "radfarm_store_queue_depth 5",
           "radfarm_round_results_kept_total 0",
           "radfarm_batches_restored_total 0",
       }) {
    EXPECT_NE(text.find(std::string(line) + "\n"), std::string::npos) << line << "\n" << text;
  }
}

TEST(MetricsTextTest, TheHistogramIsCumulativeWithSumAndCount) {
  const std::string text = FormatMetrics(Example());
  EXPECT_NE(text.find("# TYPE radfarm_checkpoint_seconds histogram\n"), std::string::npos);
  EXPECT_NE(text.find("radfarm_checkpoint_seconds_bucket{le=\"0.005\"} 1\n"), std::string::npos);
  EXPECT_NE(text.find("radfarm_checkpoint_seconds_bucket{le=\"0.025\"} 1\n"), std::string::npos);
  EXPECT_NE(text.find("radfarm_checkpoint_seconds_bucket{le=\"0.05\"} 2\n"), std::string::npos);
  EXPECT_NE(text.find("radfarm_checkpoint_seconds_bucket{le=\"10\"} 2\n"), std::string::npos);
  EXPECT_NE(text.find("radfarm_checkpoint_seconds_bucket{le=\"+Inf\"} 3\n"), std::string::npos);
  EXPECT_NE(text.find("radfarm_checkpoint_seconds_sum 20.034\n"), std::string::npos);
  EXPECT_NE(text.find("radfarm_checkpoint_seconds_count 3\n"), std::string::npos);
}

TEST(MetricsTextTest, EveryLineIsACommentOrASampleOfTheFormat) {
  // The exposition format's grammar, for the lines we write: a name, optional labels, a number.
  const std::regex sample(
      R"(^[a-zA-Z_:][a-zA-Z0-9_:]*(\{[a-zA-Z_][a-zA-Z0-9_]*="([^"\\\n]|\\.)*"\})? )"
      R"(([-+]?[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?|\+Inf|-Inf|NaN)$)");
  const std::regex comment(R"(^# (HELP|TYPE) [a-zA-Z_:][a-zA-Z0-9_:]* .+$)");
  std::istringstream lines(FormatMetrics(Example()));
  std::string line;
  int samples = 0;
  while (std::getline(lines, line)) {
    const bool ok = std::regex_match(line, sample) || std::regex_match(line, comment);
    EXPECT_TRUE(ok) << line;
    samples += line[0] != '#';
  }
  EXPECT_GT(samples, 20);
}

TEST(MetricsTextTest, LabelValuesAreEscaped) {
  FarmMetrics m;
  m.jobs_by_state = {{"a\"b\\c\nd", 1}};
  EXPECT_NE(FormatMetrics(m).find("radfarm_jobs{state=\"a\\\"b\\\\c\\nd\"} 1\n"),
            std::string::npos);
}

}  // namespace
}  // namespace radfarm::web
