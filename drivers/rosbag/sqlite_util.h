// Thin RAII over the sqlite3 C API shared by the sqlite storage reader and writer.
// Every failure throws InputError naming the file and sqlite's own message.
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <string>

namespace uwbsar::rosbag {

class SqliteDb {
 public:
  SqliteDb(const std::string& path, int flags);
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  sqlite3* get() const { return db_; }
  const std::string& path() const { return path_; }
  void Exec(const std::string& sql);
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

class SqliteStatement {
 public:
  SqliteStatement(const SqliteDb& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  /// True while a row is available; throws on errors.
  bool Step();
  void Reset();
  void Bind(int index, std::int64_t value);
  void Bind(int index, const std::string& text);
  void BindBlob(int index, const void* data, std::size_t size);
  std::int64_t Int(int column) const { return sqlite3_column_int64(stmt_, column); }
  std::string Text(int column) const;
  sqlite3_stmt* get() const { return stmt_; }

 private:
  const SqliteDb& db_;
  std::string sql_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace uwbsar::rosbag
