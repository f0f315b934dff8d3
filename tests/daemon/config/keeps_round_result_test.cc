#include <gtest/gtest.h>

#include "daemon/config/master_config.h"

namespace radfarm::daemon {
namespace {

TEST(KeepsRoundResultTest, ByDefaultOnlyResultsAcceptedFiveSecondsIntoARoundAreKept) {
  const MasterConfig config;
  EXPECT_FALSE(KeepsRoundResult(config, 0));
  EXPECT_FALSE(KeepsRoundResult(config, 4.999));
  EXPECT_TRUE(KeepsRoundResult(config, 5));
  EXPECT_TRUE(KeepsRoundResult(config, 600));
}

TEST(KeepsRoundResultTest, ZeroKeepsEveryResultAndOffKeepsNone) {
  MasterConfig config;
  config.keep_results_after_seconds = 0;
  EXPECT_TRUE(KeepsRoundResult(config, 0));
  config.keep_round_results = false;
  EXPECT_FALSE(KeepsRoundResult(config, 0));
  EXPECT_FALSE(KeepsRoundResult(config, 1e9));
}

}  // namespace
}  // namespace radfarm::daemon
