#include "slam/session/sqlite_db.h"

#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "core/errors.h"

namespace uwbsar::session {
namespace {

/// Why writing `path` failed, as the OS says it; "no space left on device" when the disk is
/// full (ENOSPC, or the folder's file system has no block left).
std::string WriteFailureCause(const std::string& path, int code, int os_error) {
  if (os_error == ENOSPC || (code & 0xff) == SQLITE_FULL) return "no space left on device";
  const std::string dir = std::filesystem::path(path).parent_path().string();
  struct statvfs fs {};
  if (::statvfs(dir.empty() ? "." : dir.c_str(), &fs) == 0 && fs.f_bavail == 0) {
    return "no space left on device";
  }
  return os_error != 0 ? std::strerror(os_error) : sqlite3_errstr(code);
}

/// Refuses a file whose last changes are not in it: a write-ahead log (`-wal`) with frames, or
/// a rollback journal (`-journal`) that is still live, both left by a program that wrote the
/// file in place (uwbsar never does: it writes a new file and renames it). Reading the file
/// alone would miss them, and letting sqlite settle them would change the user's folder.
void RefusePendingChanges(const std::string& path, const std::string& name) {
  for (const char* suffix : {"-wal", "-journal"}) {
    const std::string side = path + suffix;
    struct stat st {};
    if (::stat(side.c_str(), &st) != 0 || (S_ISREG(st.st_mode) && st.st_size == 0)) continue;
    if (S_ISREG(st.st_mode) && suffix[1] == 'j') {
      char header[8] = {};  // a finished journal kept (journal_mode=PERSIST) starts with zeros
      std::ifstream(side, std::ios::binary).read(header, sizeof header);
      if (std::all_of(header, header + sizeof header, [](char c) { return c == 0; })) continue;
    }
    throw InputError(name + ": " + side +
                     " holds changes not yet in the session (left by a program that wrote it "
                     "in place); nothing read or changed: open it once with sqlite3 to settle "
                     "them");
  }
}

/// An sqlite URI opening `path` as immutable: sqlite then reads the file alone and creates
/// nothing beside it (a session in WAL mode would otherwise get -wal and -shm files).
std::string ImmutableUri(const std::string& path) {
  std::error_code ec;
  const std::string absolute = std::filesystem::absolute(path, ec).lexically_normal().string();
  std::string uri = "file:";
  for (const char c : ec ? path : absolute) {
    if (c == '%' || c == '?' || c == '#') {
      static const char* kHex = "0123456789abcdef";
      const auto u = static_cast<unsigned char>(c);
      uri += {'%', kHex[u >> 4], kHex[u & 15]};
    } else {
      uri += c;
    }
  }
  return uri + "?immutable=1";
}

}  // namespace

SqliteDb::SqliteDb(const std::string& path, bool create, const std::string& name_in_errors)
    : name_(name_in_errors.empty() ? path : name_in_errors), writing_(create) {
  // Reading leaves the folder as it was (docs/refusals.md): immutable, after refusing
  // changes that only a -wal or -journal beside the file holds.
  if (!create) RefusePendingChanges(path, name_);
  const int flags = create ? (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE)
                           : (SQLITE_OPEN_READONLY | SQLITE_OPEN_URI);
  const std::string target = create ? path : ImmutableUri(path);
  if (sqlite3_open_v2(target.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    const int code = db_ ? sqlite3_extended_errcode(db_) : SQLITE_NOMEM;
    const int os_error = db_ ? sqlite3_system_errno(db_) : 0;
    sqlite3_close(db_);
    db_ = nullptr;
    if (create) {
      throw std::runtime_error(name_ + ": cannot write: " +
                               (os_error != 0 ? WriteFailureCause(path, code, os_error) : message));
    }
    throw InputError(name_ + ": cannot open the session: " + message);
  }
  sqlite3_extended_result_codes(db_, 1);
}

SqliteDb::~SqliteDb() { sqlite3_close(db_); }

void SqliteDb::Fail(const std::string& what) const {
  const int code = sqlite3_extended_errcode(db_);
  if (writing_) {
    switch (code & 0xff) {
      case SQLITE_FULL:
      case SQLITE_IOERR:
      case SQLITE_READONLY:
      case SQLITE_PERM:
      case SQLITE_CANTOPEN:
        throw std::runtime_error(
            name_ + ": cannot write: " + WriteFailureCause(name_, code, sqlite3_system_errno(db_)));
      default:
        break;
    }
  }
  throw InputError(name_ + ": " + what + ": " + sqlite3_errmsg(db_));
}

void SqliteDb::Exec(const std::string& sql) {
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) {
    Fail("'" + sql.substr(0, 40) + "'");
  }
}

bool SqliteDb::HasTable(const std::string& name) {
  SqliteStatement s(*this, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  s.Bind(1, name);
  return s.Step();
}

SqliteStatement::SqliteStatement(SqliteDb& db, const std::string& sql) : db_(db) {
  if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) {
    db.Fail("not a uwbsar session (" + sql.substr(0, sql.find(' ', 7)) + ")");
  }
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(stmt_); }

void SqliteStatement::Bind(int index, std::int64_t value) {
  sqlite3_bind_int64(stmt_, index, static_cast<sqlite3_int64>(value));
}
void SqliteStatement::Bind(int index, double value) { sqlite3_bind_double(stmt_, index, value); }
void SqliteStatement::Bind(int index, const std::string& text) {
  sqlite3_bind_text(stmt_, index, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
}
void SqliteStatement::BindBlob(int index, const std::vector<unsigned char>& bytes) {
  sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(), SQLITE_TRANSIENT);
}

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  db_.Fail("damaged session");
}

void SqliteStatement::Run() {
  while (Step()) {
  }
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

int SqliteStatement::ColumnCount() const { return sqlite3_column_count(stmt_); }
std::string SqliteStatement::ColumnName(int column) const {
  const char* name = sqlite3_column_name(stmt_, column);
  return name ? name : "";
}
bool SqliteStatement::IsNull(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}
bool SqliteStatement::IsInteger(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_INTEGER;
}
bool SqliteStatement::IsReal(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_FLOAT;
}
bool SqliteStatement::IsBlob(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_BLOB;
}
std::int64_t SqliteStatement::Int(int column) const {
  return static_cast<std::int64_t>(sqlite3_column_int64(stmt_, column));
}
double SqliteStatement::Double(int column) const {
  if (sqlite3_column_type(stmt_, column) == SQLITE_NULL) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return sqlite3_column_double(stmt_, column);
}
std::string SqliteStatement::Text(int column) const {
  const unsigned char* text = sqlite3_column_text(stmt_, column);
  const int n = sqlite3_column_bytes(stmt_, column);
  return text ? std::string(reinterpret_cast<const char*>(text), static_cast<std::size_t>(n))
              : std::string();
}
std::vector<unsigned char> SqliteStatement::Blob(int column) const {
  const auto* data = static_cast<const unsigned char*>(sqlite3_column_blob(stmt_, column));
  const int n = sqlite3_column_bytes(stmt_, column);
  if (data == nullptr || n <= 0) return {};
  return std::vector<unsigned char>(data, data + n);
}

}  // namespace uwbsar::session
