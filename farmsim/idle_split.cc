#include "farmsim/idle_split.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "core/batch.h"

namespace radfarm::sim {

IdleSplit SplitIdleTime(const SwarmReport& report, size_t agents, double wall_seconds) {
  IdleSplit split;
  if (agents == 0 || wall_seconds <= 0) return split;
  double span_sum = 0, span_busy = 0;
  std::vector<std::pair<double, double>> spans;
  for (const auto& [number, span] : report.rounds) {
    if (number == kGatherRound || span.first_assignment < 0 || span.last_result < 0) continue;
    span_sum += span.last_result - span.first_assignment;
    span_busy += span.busy_seconds;
    spans.emplace_back(span.first_assignment, span.last_result);
  }
  double ahead_within = 0, ahead_between = 0;
  for (const SimAgentStats& a : report.agents) {
    for (const auto& [start, end] : a.ahead_compute) {
      double within = 0;
      for (const auto& [first, last] : spans) {
        within += std::max(0.0, std::min(end, last) - std::max(start, first));
      }
      within = std::min(within, end - start);
      ahead_within += within;
      ahead_between += (end - start) - within;
    }
  }
  double starts = 0, tails = 0;
  for (const SimAgentStats& a : report.agents) {
    for (const auto& [number, span] : a.rounds) {
      const auto round = report.rounds.find(number);
      if (number == kGatherRound || round == report.rounds.end() || span.first_assignment < 0 ||
          span.last_result < 0) {
        continue;
      }
      starts += span.first_assignment - round->second.first_assignment;
      tails += round->second.last_result - span.last_result;
    }
  }
  const double n = double(agents);
  const double agent_seconds = n * wall_seconds;
  split.between_rounds =
      std::max(0.0, n * (wall_seconds - span_sum) - ahead_between) / agent_seconds;
  split.within_rounds = std::max(0.0, n * span_sum - span_busy - ahead_within) / agent_seconds;
  split.round_starts = starts / agent_seconds;
  split.round_tails = tails / agent_seconds;
  return split;
}

}  // namespace radfarm::sim
