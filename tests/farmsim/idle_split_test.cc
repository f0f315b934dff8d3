// SplitIdleTime: farm_bench's split of simulated agents' idle time between and within rounds,
// with the final gather's batches computed ahead counted as busy wherever they fall.
#include "farmsim/idle_split.h"

#include <gtest/gtest.h>

#include "core/batch.h"

namespace radfarm::sim {
namespace {

RoundSpan Span(double first, double last, double busy) {
  RoundSpan s;
  s.first_assignment = first;
  s.last_result = last;
  s.busy_seconds = busy;
  return s;
}

// Two agents, rounds 0 over [0, 1] and 1 over [1.5, 2.5], a wall of 2.5 s. Agent a works through
// both rounds and computes a gather batch ahead between them; agent b ends round 0 at 0.8 s, and
// computes a gather batch ahead over [0.9, 1.2]: 0.1 s in round 0's tail, 0.2 s after it.
SwarmReport TwoAgents() {
  SwarmReport report;
  SimAgentStats a;
  a.rounds[0] = Span(0, 1, 1);
  a.rounds[1] = Span(1.5, 2.5, 1);
  a.ahead_compute = {{1.0, 1.5}};
  SimAgentStats b;
  b.rounds[0] = Span(0, 0.8, 0.8);
  b.rounds[1] = Span(1.5, 2.5, 1);
  b.ahead_compute = {{0.9, 1.2}};
  report.agents = {a, b};
  report.rounds[0] = Span(0, 1, 1.8);
  report.rounds[1] = Span(1.5, 2.5, 2);
  report.rounds[kGatherRound] = Span(0.9, 1.5, 0.8);  // no span of its own: ignored
  return report;
}

TEST(IdleSplitTest, TimeOnTheGatherAheadIsBusyWithinARoundOrBetweenRounds) {
  const IdleSplit split = SplitIdleTime(TwoAgents(), 2, 2.5);
  // Within: 2 agents x 2 s of spans, 3.8 s computing the rounds, 0.1 s the gather ahead.
  EXPECT_NEAR(split.within_rounds, (4.0 - 3.8 - 0.1) / 5, 1e-12);
  // Between: 2 agents x 0.5 s, 0.5 + 0.2 s of it on the gather ahead.
  EXPECT_NEAR(split.between_rounds, (1.0 - 0.7) / 5, 1e-12);
  EXPECT_NEAR(split.round_starts, 0, 1e-12);
  EXPECT_NEAR(split.round_tails, 0.2 / 5, 1e-12);
}

TEST(IdleSplitTest, WithoutTheGatherAheadEveryAgentIdlesBetweenRounds) {
  SwarmReport report = TwoAgents();
  for (SimAgentStats& a : report.agents) a.ahead_compute.clear();
  const IdleSplit split = SplitIdleTime(report, 2, 2.5);
  EXPECT_NEAR(split.within_rounds, (4.0 - 3.8) / 5, 1e-12);
  EXPECT_NEAR(split.between_rounds, 1.0 / 5, 1e-12);
}

TEST(IdleSplitTest, NoAgentsOrNoWallTimeGiveZero) {
  const IdleSplit none = SplitIdleTime(TwoAgents(), 0, 2.5);
  EXPECT_EQ(none.within_rounds, 0);
  EXPECT_EQ(none.between_rounds, 0);
  EXPECT_EQ(SplitIdleTime(TwoAgents(), 2, 0).round_tails, 0);
}

}  // namespace
}  // namespace radfarm::sim
