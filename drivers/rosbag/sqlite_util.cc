#include "drivers/rosbag/sqlite_util.h"

#include <sys/statvfs.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/errors.h"

namespace uwbsar::rosbag {

SqliteDb::SqliteDb(const std::string& path, int flags) : path_(path) {
  if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path + ": cannot open as sqlite3: " + message);
  }
  sqlite3_extended_result_codes(db_, 1);
}

SqliteDb::~SqliteDb() { sqlite3_close(db_); }

void SqliteDb::Fail(const std::string& what) const {
  const int code = sqlite3_extended_errcode(db_);
  const std::string message = path_ + ": sqlite3 " + what + ": " + sqlite3_errmsg(db_);
  // A failing disk is an I/O failure naming its cause (the OS error: no space left on
  // device, file too large, ...), not a bad input file.
  const int os_error = sqlite3_system_errno(db_);
  switch (code & 0xff) {
    case SQLITE_FULL:
      throw std::runtime_error(message + " (" +
                               (os_error != 0 && os_error != ENOSPC
                                    ? std::string(std::strerror(os_error))
                                    : std::string("no space left on device")) +
                               ")");
    case SQLITE_IOERR:
    case SQLITE_READONLY:
    case SQLITE_PERM: {
      std::string cause = os_error != 0 ? std::strerror(os_error) : sqlite3_errstr(code);
      const std::string dir = std::filesystem::path(path_).parent_path().string();
      struct statvfs fs {};
      if (os_error == 0 && ::statvfs(dir.empty() ? "." : dir.c_str(), &fs) == 0 &&
          fs.f_bavail == 0) {
        cause = "no space left on device";
      }
      throw std::runtime_error(message + " (" + cause + ")");
    }
    default:
      throw InputError(message);
  }
}

void SqliteDb::Exec(const std::string& sql) {
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) {
    Fail("'" + sql.substr(0, 40) + "'");
  }
}

SqliteStatement::SqliteStatement(const SqliteDb& db, const std::string& sql) : db_(db), sql_(sql) {
  if (sqlite3_prepare_v2(db.get(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) {
    db.Fail("query '" + sql.substr(0, 60) + "'");
  }
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(stmt_); }

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  db_.Fail("query '" + sql_.substr(0, 60) + "'");
}

void SqliteStatement::Reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

void SqliteStatement::Bind(int index, std::int64_t value) {
  if (sqlite3_bind_int64(stmt_, index, value) != SQLITE_OK) db_.Fail("bind");
}

void SqliteStatement::Bind(int index, const std::string& text) {
  if (sqlite3_bind_text(stmt_, index, text.data(), static_cast<int>(text.size()),
                        SQLITE_TRANSIENT) != SQLITE_OK) {
    db_.Fail("bind");
  }
}

void SqliteStatement::BindBlob(int index, const void* data, std::size_t size) {
  if (sqlite3_bind_blob64(stmt_, index, data, size, SQLITE_STATIC) != SQLITE_OK) {
    db_.Fail("bind");
  }
}

std::string SqliteStatement::Text(int column) const {
  const auto* p = sqlite3_column_text(stmt_, column);
  return p ? std::string(reinterpret_cast<const char*>(p),
                         static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column)))
           : std::string();
}

}  // namespace uwbsar::rosbag
