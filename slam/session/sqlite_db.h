// A small RAII layer over the sqlite3 C API for the session file: one connection, prepared
// statements with typed binds and column reads. Reading, every sqlite failure becomes an
// InputError naming the file and what was being done (a damaged or foreign file is bad input);
// writing (a connection opened with `create`), a full or failing disk is an I/O failure: a
// std::runtime_error "<path>: cannot write: <cause>" (cause "no space left on device" when the
// disk is full), everything else an InputError as when reading.
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
  int ColumnCount() const;
  std::string ColumnName(int column) const;
  bool IsNull(int column) const;
  /// True when the value is stored as an integer (not a real, text or blob).
  bool IsInteger(int column) const;
  bool IsReal(int column) const;
  bool IsBlob(int column) const;
  std::int64_t Int(int column) const;
  double Double(int column) const;  ///< NULL reads as NaN
  std::string Text(int column) const;
  std::vector<unsigned char> Blob(int column) const;

 private:
  SqliteDb& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

class SqliteDb {
 public:
  /// Opens `path` read-only, or creates it (read-write) with `create`; errors name
  /// `name_in_errors` (default: `path`), e.g. the final file a temporary one becomes. Throws
  /// InputError (reading) or std::runtime_error (creating where it cannot be written).
  SqliteDb(const std::string& path, bool create, const std::string& name_in_errors = "");
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  void Exec(const std::string& sql);
  bool HasTable(const std::string& name);
  /// Throws InputError "PATH: <what>: <sqlite message>", or, on a connection that writes and a
  /// full or failing disk, std::runtime_error "PATH: cannot write: <cause>".
  [[noreturn]] void Fail(const std::string& what) const;
  sqlite3* handle() { return db_; }
  const std::string& path() const { return name_; }

 private:
  sqlite3* db_ = nullptr;
  std::string name_;
  bool writing_ = false;
};

}  // namespace uwbsar::session
