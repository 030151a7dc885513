// Test helper: runs SQL on a session file, as a hostile or damaged file would have it.
#pragma once

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <string>

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

}  // namespace uwbsar::testing
