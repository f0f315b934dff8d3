// DisplayPieces and the frames of display_run.h: a step's points leased in pieces, the first
// result of each kept, lost and returned pieces leased again, late results told apart, and the
// values handed back in point order whoever traced them.
#include "daemon/jobs/display_pieces.h"

#include <gtest/gtest.h>

#include <chrono>

#include "daemon/jobs/display_run.h"

namespace radfarm::daemon {
namespace {

using scheduler::TimePoint;
using std::chrono::milliseconds;

const TimePoint kStart{milliseconds(1000)};
constexpr milliseconds kLease{5000};

// Values for points [begin, end): point i's direct light is i, so the order shows.
PointValues ValuesFor(const PieceLease& piece) {
  PointValues v;
  for (size_t i = piece.begin; i < piece.end; ++i) v.direct.push_back(Rgb(double(i), 0, 0));
  v.rays = piece.end - piece.begin;
  return v;
}

TEST(DisplayPiecesTest, CutsThePointsAndHandsTheValuesBackInOrder) {
  DisplayPieces pieces(/*step=*/2, /*points=*/10, /*piece_points=*/4, kLease);
  ASSERT_EQ(pieces.pieces(), 3u);
  const auto a = pieces.Next(1, kStart), b = pieces.Next(2, kStart), c = pieces.Next(1, kStart);
  ASSERT_TRUE(a && b && c);
  EXPECT_FALSE(pieces.Next(3, kStart)) << "every piece is leased and none overdue";
  EXPECT_EQ(c->begin, 8u);
  EXPECT_EQ(c->end, 10u);
  EXPECT_EQ(a->piece_id >> 32, 2u) << "the id carries the step";
  EXPECT_EQ(pieces.HeldBy(1), 2u);
  // Out of order: the last piece first.
  EXPECT_EQ(pieces.OnResult(1, c->piece_id, c->attempt, ValuesFor(*c)),
            DisplayPieces::Verdict::kAccepted);
  EXPECT_EQ(pieces.OnResult(2, b->piece_id, b->attempt, ValuesFor(*b)),
            DisplayPieces::Verdict::kAccepted);
  EXPECT_FALSE(pieces.Complete());
  EXPECT_EQ(pieces.OnResult(1, a->piece_id, a->attempt, ValuesFor(*a)),
            DisplayPieces::Verdict::kAccepted);
  ASSERT_TRUE(pieces.Complete());
  const PointValues all = pieces.TakeValues();
  ASSERT_EQ(all.direct.size(), 10u);
  for (size_t i = 0; i < 10; ++i) EXPECT_EQ(all.direct[i].r, double(i));
  EXPECT_EQ(all.rays, 10u);
}

TEST(DisplayPiecesTest, ALostAgentsPiecesAreLeasedAgainFirst) {
  DisplayPieces pieces(0, 12, 4, kLease);
  const auto a = pieces.Next(1, kStart);
  const auto b = pieces.Next(1, kStart);
  pieces.OnAgentLost(1);
  EXPECT_EQ(pieces.HeldBy(1), 0u);
  const auto again = pieces.Next(2, kStart);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->begin, b->begin) << "requeued at the front";
  // The lost agent answers anyway: not its live lease any more, and the piece is not done.
  EXPECT_EQ(pieces.OnResult(1, a->piece_id, a->attempt, ValuesFor(*a)),
            DisplayPieces::Verdict::kUnknown);
}

TEST(DisplayPiecesTest, AnOverduePieceGoesToAnotherAgentAndTheFirstResultWins) {
  DisplayPieces pieces(0, 4, 4, kLease);
  const auto first = pieces.Next(1, kStart);
  ASSERT_TRUE(first);
  EXPECT_FALSE(pieces.Next(2, kStart + kLease / 2)) << "not overdue yet";
  EXPECT_FALSE(pieces.Next(1, kStart + 2 * kLease)) << "never to the agent that holds it";
  const auto copy = pieces.Next(2, kStart + 2 * kLease);
  ASSERT_TRUE(copy);
  EXPECT_EQ(copy->piece_id, first->piece_id);
  EXPECT_NE(copy->attempt, first->attempt);
  EXPECT_EQ(pieces.OnResult(2, copy->piece_id, copy->attempt, ValuesFor(*copy)),
            DisplayPieces::Verdict::kAccepted);
  EXPECT_EQ(pieces.OnResult(1, first->piece_id, first->attempt, ValuesFor(*first)),
            DisplayPieces::Verdict::kLate);
  EXPECT_TRUE(pieces.Complete());
}

TEST(DisplayPiecesTest, AReturnedPieceIsQueuedAgainAndOtherStepsAreUnknown) {
  DisplayPieces pieces(1, 8, 4, kLease);
  const auto a = pieces.Next(1, kStart);
  pieces.Return(1, a->piece_id, a->attempt + 100);  // not its attempt: ignored
  EXPECT_EQ(pieces.HeldBy(1), 1u);
  pieces.Return(1, a->piece_id, a->attempt);
  EXPECT_EQ(pieces.HeldBy(1), 0u);
  EXPECT_EQ(pieces.Next(2, kStart)->begin, a->begin);
  const uint64_t earlier_step = a->piece_id & 0xffffffffu;  // step 0's piece of that index
  EXPECT_FALSE(pieces.PointsOf(earlier_step));
  EXPECT_EQ(pieces.OnResult(2, earlier_step, 1, {}), DisplayPieces::Verdict::kUnknown);
}

PointWork SmallWork() {
  PointWork work;
  for (int i = 0; i < 5; ++i) work.points.push_back({{double(i), 0, 0}, {0, 1, 0}});
  work.seed = 99;
  work.near_radius = 0.5;
  work.direct = true;
  work.gather = {true, false, true, true, false};
  work.gather_rays = 64;
  return work;
}

TEST(DisplayRunTest, APieceTravelsAsItsPointsKeyedAsInTheWhole) {
  const PointWork work = SmallWork();
  const PieceLease piece{(uint64_t{3} << 32) | 1, 7, 2, 5, kStart};
  const protocol::PointLeaseMsg m = MakePointLease(4, piece, work, protocol::SceneHash{}, 60000);
  EXPECT_EQ(m.lease.job_id, 4u);
  EXPECT_EQ(m.lease.batch_id, piece.piece_id);
  EXPECT_EQ(m.lease.attempt_id, 7u);
  EXPECT_EQ(m.first_index, 2u);
  ASSERT_EQ(m.points.size(), 3u);
  EXPECT_EQ(m.points[0].position.x, 2.0);
  EXPECT_EQ(m.gather, (std::vector<uint8_t>{1, 1, 0}));
  EXPECT_EQ(m.gather_rays, 64u);
  EXPECT_EQ(m.seed, 99u);
}

TEST(DisplayRunTest, AResultMustHoldOneValuePerPointOfWhatWasAsked) {
  const PointWork work = SmallWork();
  protocol::PointResultMsg r;
  r.near = {0, 1, 1};
  r.direct.assign(3, Rgb(1, 2, 3));
  r.gathered.assign(3, Rgb());
  r.rays = 300;
  Result<PointValues> ok = ValuesOfResult(r, work, 2, 5);
  ASSERT_TRUE(ok.ok()) << ok.error();
  EXPECT_EQ(ok->near, (std::vector<bool>{false, true, true}));
  EXPECT_EQ(ok->rays, 300u);
  protocol::PointResultMsg short_one = r;
  short_one.direct.pop_back();
  Result<PointValues> bad = ValuesOfResult(short_one, work, 2, 5);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "PointResult: 2 direct values where 3 are due");
  PointWork no_gather = work;
  no_gather.gather.clear();
  bad = ValuesOfResult(r, no_gather, 2, 5);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "PointResult: 3 gathered values where 0 are due");
}

TEST(DisplayRunTest, PiecesAreAQuarterOfAnAgentsShareWithinBounds) {
  EXPECT_EQ(PiecePoints(100, 1), kMinLeasePoints);
  EXPECT_EQ(PiecePoints(400000, 1), protocol::kMaxLeasePoints);
  EXPECT_EQ(PiecePoints(80000, 4), 5000u);
  EXPECT_EQ(PiecePoints(80000, 0), protocol::kMaxLeasePoints);
}

// The farm's ETA while the display is drawn: the forecast rays still to cast at the pace so far.
TEST(DisplayRunTest, TheSecondsLeftAreTheForecastsRestAtThePaceSoFar) {
  DisplayRun run;
  run.forecast_rays = 40'000'000;
  run.started_ms = 1'000;
  EXPECT_FALSE(DisplaySecondsLeft(run, 3'000));  // no step applied yet: no pace
  run.rays_done = 10'000'000;
  ASSERT_TRUE(DisplaySecondsLeft(run, 3'000));
  EXPECT_DOUBLE_EQ(*DisplaySecondsLeft(run, 3'000), 6.0);  // 10 M in 2 s, 30 M to go
  // Past its forecast the last steps' size is unknown: no estimate rather than a wrong one.
  run.rays_done = 40'000'000;
  EXPECT_FALSE(DisplaySecondsLeft(run, 9'000));
}

}  // namespace
}  // namespace radfarm::daemon
