// Store errors classified where SQLite's result codes become them (store/sqlite_error.h): the
// kind each code gets, and which kinds hold a job rather than fail it.
#include "store/sqlite_error.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

namespace radfarm::store {
namespace {

TEST(SqliteErrorTest, EachCodeGetsTheKindOfItsClass) {
  const struct {
    int code;
    ErrorKind kind;
  } cases[] = {
      {SQLITE_FULL, ErrorKind::kDiskFull},
      {SQLITE_IOERR, ErrorKind::kIo},
      {SQLITE_IOERR_WRITE, ErrorKind::kIo},
      {SQLITE_IOERR_FSYNC, ErrorKind::kIo},
      {SQLITE_IOERR_NOMEM, ErrorKind::kOther},  // memory, not the disk
      {SQLITE_BUSY, ErrorKind::kBusy},
      {SQLITE_BUSY_SNAPSHOT, ErrorKind::kBusy},
      {SQLITE_LOCKED, ErrorKind::kBusy},
      {SQLITE_CORRUPT, ErrorKind::kCorrupt},
      {SQLITE_CORRUPT_INDEX, ErrorKind::kCorrupt},
      {SQLITE_NOTADB, ErrorKind::kCorrupt},
      {SQLITE_CONSTRAINT, ErrorKind::kConstraint},
      {SQLITE_CONSTRAINT_FOREIGNKEY, ErrorKind::kConstraint},
      {SQLITE_CONSTRAINT_CHECK, ErrorKind::kConstraint},
      {SQLITE_CANTOPEN, ErrorKind::kOther},
      {SQLITE_READONLY, ErrorKind::kOther},
      {SQLITE_ERROR, ErrorKind::kOther},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(SqliteCodeName(c.code));
    EXPECT_EQ(SqliteErrorKind(c.code), c.kind);
    const Error error = SqliteError("/x/jobs.db", "save checkpoint", c.code, nullptr);
    EXPECT_EQ(error.kind, c.kind);
    EXPECT_EQ(error.message.rfind("job store /x/jobs.db: save checkpoint: SQLITE_", 0), 0u)
        << error.message;
  }
}

TEST(SqliteErrorTest, OnlyAFullDiskAndAnIoErrorAreStoreFaults) {
  EXPECT_TRUE(IsStoreFault(ErrorKind::kDiskFull));
  EXPECT_TRUE(IsStoreFault(ErrorKind::kIo));
  EXPECT_FALSE(IsStoreFault(ErrorKind::kBusy));
  EXPECT_FALSE(IsStoreFault(ErrorKind::kCorrupt));
  EXPECT_FALSE(IsStoreFault(ErrorKind::kConstraint));
  EXPECT_FALSE(IsStoreFault(ErrorKind::kOther));
}

// The kind decides, not the words: a message that quotes a code is still of its own kind.
TEST(SqliteErrorTest, AMessageNamingACodeDoesNotMakeAFault) {
  const Error quoted{"scene 'SQLITE_FULL.obj': no such file"};
  EXPECT_FALSE(IsStoreFault(quoted.kind));
}

}  // namespace
}  // namespace radfarm::store
