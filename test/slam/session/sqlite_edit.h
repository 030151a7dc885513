// Test helper: runs SQL on a session file, as a hostile or damaged file would have it.
#pragma once

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <vector>

namespace uwbsar::testing {

/// Runs `sql` on the sqlite file at `path` (fails the test when sqlite refuses it).
inline void RunSql(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string message = error ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << sql << ": " << message;
}

/// The first column of the first row `query` gives, as text ("" for none).
inline std::string SqlText(const std::string& path, const std::string& query) {
  sqlite3* db = nullptr;
  std::string out;
  if (sqlite3_open(path.c_str(), &db) == SQLITE_OK) {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db, query.c_str(), -1, &s, nullptr) == SQLITE_OK &&
        sqlite3_step(s) == SQLITE_ROW && sqlite3_column_text(s, 0) != nullptr) {
      out = reinterpret_cast<const char*>(sqlite3_column_text(s, 0));
    }
    sqlite3_finalize(s);
  }
  sqlite3_close(db);
  return out;
}

/// Inverts `count` bytes of blob `column` in `table`'s row `rowid`, from the blob's middle on
/// (inside a tile's zstd body, past its header), as a bad disk sector or a bad copy would.
inline void FlipBlobBytes(const std::string& path, const std::string& table,
                          const std::string& column, std::int64_t rowid, int count) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  const std::string where = " WHERE rowid = " + std::to_string(rowid);
  ASSERT_EQ(sqlite3_prepare_v2(db, ("SELECT " + column + " FROM " + table + where).c_str(), -1, &s,
                               nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  const auto* bytes = static_cast<const unsigned char*>(sqlite3_column_blob(s, 0));
  std::vector<unsigned char> blob(bytes, bytes + sqlite3_column_bytes(s, 0));
  sqlite3_finalize(s);
  ASSERT_GT(blob.size(), 2u * static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) blob[blob.size() / 2 + static_cast<std::size_t>(i)] ^= 0xff;
  ASSERT_EQ(sqlite3_prepare_v2(db, ("UPDATE " + table + " SET " + column + " = ?" + where).c_str(),
                               -1, &s, nullptr),
            SQLITE_OK);
  sqlite3_bind_blob64(s, 1, blob.data(), blob.size(), SQLITE_TRANSIENT);
  EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
  sqlite3_finalize(s);
  sqlite3_close(db);
}

}  // namespace uwbsar::testing
