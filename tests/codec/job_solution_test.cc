#include "codec/job_solution.h"

#include <gtest/gtest.h>

#include <limits>

namespace radfarm::codec {
namespace {

JobSolution Sample() {
  JobSolution s;
  s.bundle = {1, 2, 3, 4, 5};
  s.radiosity = {{0.1, 0.2, 0.3}, {1e-300, 0, 7}};
  s.unshot = {{0, 0, 0}, {1e-5, 2e-5, 3e-5}};
  s.stats.rays = 123456789;
  s.stats.rounds = 7;
  s.stats.seconds = 1.25;
  s.stats.sampler = "sobol";
  s.stats.stop_reason = "converged";
  s.stats.emitted_power = 3.5;
  return s;
}

TEST(JobSolutionTest, RoundTripsExactly) {
  const JobSolution s = Sample();
  const std::vector<uint8_t> blob = EncodeJobSolution(s);
  Result<JobSolution> back = DecodeJobSolution(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->bundle, s.bundle);
  ASSERT_EQ(back->radiosity.size(), 2u);
  EXPECT_EQ(back->radiosity[1].r, 1e-300);
  EXPECT_EQ(back->unshot[1].b, 3e-5);
  EXPECT_EQ(back->stats.rays, s.stats.rays);
  EXPECT_EQ(back->stats.stop_reason, "converged");
  EXPECT_TRUE(back->scene.empty());  // not refined
  EXPECT_EQ(EncodeJobSolution(*back), blob);
}

TEST(JobSolutionTest, CarriesTheRefinedScene) {
  JobSolution s = Sample();
  s.scene = {9, 8, 7, 6};
  const std::vector<uint8_t> blob = EncodeJobSolution(s);
  EXPECT_NE(blob, EncodeJobSolution(Sample()));
  Result<JobSolution> back = DecodeJobSolution(blob);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->scene, s.scene);
  EXPECT_EQ(back->radiosity.size(), 2u);
  EXPECT_EQ(EncodeJobSolution(*back), blob);
}

TEST(JobSolutionTest, RejectsMismatchedSizesAndNonFiniteValues) {
  JobSolution s = Sample();
  s.unshot.pop_back();
  EXPECT_FALSE(DecodeJobSolution(EncodeJobSolution(s)).ok());
  s = Sample();
  s.radiosity[0].g = std::numeric_limits<double>::quiet_NaN();
  Result<JobSolution> r = DecodeJobSolution(EncodeJobSolution(s));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("patch 0"), std::string::npos) << r.error();
  const std::vector<uint8_t> blob = EncodeJobSolution(Sample());
  EXPECT_FALSE(DecodeJobSolution(std::span(blob).first(blob.size() / 2)).ok());
}

// Over-relaxation leaves negative unshot radiosity (and, through noise, may leave a slightly
// negative radiosity estimate): finite values of either sign are a valid solution.
TEST(JobSolutionTest, AcceptsNegativeFiniteValues) {
  JobSolution s = Sample();
  s.unshot[1] = {-1e-5, 2e-5, -3e-5};
  s.radiosity[0].b = -1e-9;
  Result<JobSolution> back = DecodeJobSolution(EncodeJobSolution(s));
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->unshot[1], s.unshot[1]);
  EXPECT_EQ(back->radiosity[0], s.radiosity[0]);
  s.unshot[1].g = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(DecodeJobSolution(EncodeJobSolution(s)).ok());
}

}  // namespace
}  // namespace radfarm::codec
