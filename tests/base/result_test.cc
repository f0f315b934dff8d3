#include "base/result.h"

#include <gtest/gtest.h>

#include <string>

namespace radfarm {
namespace {

Status Fails(const std::string& why) { return Error{why}; }
Status Succeeds() { return Ok{}; }
Result<int> Number(bool ok) {
  if (!ok) return Error{"no number"};
  return 7;
}

// Counts its calls, so a test can see the macro evaluates its argument once.
Status Counted(int* calls, bool ok) {
  ++*calls;
  return ok ? Status(Ok{}) : Status(Error{"counted"});
}

Result<std::string> PassesStatusUp(const std::string& why) {
  RADFARM_RETURN_IF_ERROR(Fails(why));
  return std::string("not reached");
}

Result<double> PassesResultUp(bool ok) {
  Result<int> n = Number(ok);
  RADFARM_RETURN_IF_ERROR(n);
  return *n * 0.5;
}

Status RunsOn(int* calls, bool ok) {
  RADFARM_RETURN_IF_ERROR(Succeeds());
  RADFARM_RETURN_IF_ERROR(Counted(calls, ok));
  ++*calls;  // reached only on success
  return Ok{};
}

TEST(ResultTest, HoldsAValueOrAnError) {
  Result<int> good = 3;
  ASSERT_TRUE(good.ok());
  EXPECT_TRUE(static_cast<bool>(good));
  EXPECT_EQ(*good, 3);
  Result<int> bad = Error{"x.obj:2: bad"};
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "x.obj:2: bad");
}

TEST(ReturnIfErrorTest, ReturnsTheErrorOfAStatusAsAnyResult) {
  Result<std::string> r = PassesStatusUp("disk full");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error(), "disk full");
}

TEST(ReturnIfErrorTest, ReturnsTheErrorOfAResultAndGoesOnOnSuccess) {
  Result<double> bad = PassesResultUp(false);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error(), "no number");
  Result<double> good = PassesResultUp(true);
  ASSERT_TRUE(good.ok()) << good.error();
  EXPECT_EQ(*good, 3.5);
}

Status FailsWithKind(ErrorKind kind) { return Error{"no room", kind}; }
Result<int> PassesKindUp(ErrorKind kind) {
  RADFARM_RETURN_IF_ERROR(FailsWithKind(kind));
  return 1;
}

TEST(ReturnIfErrorTest, KeepsTheErrorsKind) {
  EXPECT_EQ(Status(Error{"plain"}).error_kind(), ErrorKind::kOther);
  for (ErrorKind kind : {ErrorKind::kOther, ErrorKind::kDiskFull, ErrorKind::kIo, ErrorKind::kBusy,
                         ErrorKind::kCorrupt, ErrorKind::kConstraint}) {
    Result<int> r = PassesKindUp(kind);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error(), "no room");
    EXPECT_EQ(r.error_kind(), kind);
  }
}

TEST(ReturnIfErrorTest, EvaluatesItsArgumentOnce) {
  int calls = 0;
  Status failed = RunsOn(&calls, false);
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error(), "counted");
  EXPECT_EQ(calls, 1);
  calls = 0;
  EXPECT_TRUE(RunsOn(&calls, true).ok());
  EXPECT_EQ(calls, 2);
}

}  // namespace
}  // namespace radfarm
