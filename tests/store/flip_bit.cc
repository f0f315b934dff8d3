#include "tests/store/flip_bit.h"

#include <gtest/gtest.h>

#include "store/database.h"

namespace radfarm::store {

void FlipBit(const std::string& path, const std::string& table, const std::string& column,
             const std::string& where) {
  Result<Database> db = Database::Open(path, {});
  ASSERT_TRUE(db.ok()) << db.error();
  Result<Statement> read = db->Prepare("SELECT " + column + " FROM " + table + " WHERE " + where);
  ASSERT_TRUE(read.ok()) << read.error();
  ASSERT_TRUE(*read->Step());
  std::vector<uint8_t> bytes = read->Blob(0);
  ASSERT_FALSE(bytes.empty());
  bytes[bytes.size() / 2] ^= 0x10;
  Result<Statement> write =
      db->Prepare("UPDATE " + table + " SET " + column + " = ?1 WHERE " + where);
  ASSERT_TRUE(write.ok()) << write.error();
  write->BindBlob(1, bytes);
  ASSERT_TRUE(write->Run().ok());
}

}  // namespace radfarm::store
