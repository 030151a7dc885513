// A small RAII layer over the sqlite3 C API for the session file: one connection, prepared
// statements with typed binds and column reads. Every sqlite failure becomes an InputError
// naming the file and what was being done (a damaged or foreign file is bad input).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace uwbsar::session {

class SqliteDb;

class SqliteStatement {
 public:
  SqliteStatement(SqliteDb& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  // Binds are 1-based like sqlite's.
  void Bind(int index, std::int64_t value);
  void Bind(int index, int value) { Bind(index, static_cast<std::int64_t>(value)); }
  void Bind(int index, double value);
  void Bind(int index, const std::string& text);
  void BindBlob(int index, const std::vector<unsigned char>& bytes);
  /// Runs one step: true when a row is available, false when done.
  bool Step();
  /// Runs an insert/update to completion and resets for the next binds.
  void Run();

  // Columns are 0-based like sqlite's.
  std::int64_t Int(int column) const;
  double Double(int column) const;
  std::string Text(int column) const;
  std::vector<unsigned char> Blob(int column) const;

 private:
  SqliteDb& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

class SqliteDb {
 public:
  /// Opens `path` read-only, or creates it (read-write) with `create`. Throws InputError.
  SqliteDb(const std::string& path, bool create);
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  void Exec(const std::string& sql);
  bool HasTable(const std::string& name);
  /// Throws InputError "PATH: <what>: <sqlite message>".
  [[noreturn]] void Fail(const std::string& what) const;
  sqlite3* handle() { return db_; }
  const std::string& path() const { return path_; }

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace uwbsar::session
