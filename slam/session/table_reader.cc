#include "slam/session/table_reader.h"

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "core/errors.h"
#include "slam/session/blob_checksum.h"

namespace uwbsar::session {
namespace {

std::string Quoted(const std::string& name) {
  std::string out = "\"";
  for (char c : name) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

}  // namespace

TableReader::TableReader(SqliteDb& db, const std::string& table,
                         const std::vector<std::string>& required,
                         const std::vector<std::string>& optional)
    : db_(db), table_(table) {
  if (!db.HasTable(table))
    throw InputError(db.path() + ": not a uwbsar session (no table " + table + ")");
  std::map<std::string, bool> present;
  {
    SqliteStatement names(db, "SELECT * FROM " + Quoted(table) + " LIMIT 0");
    for (int i = 0; i < names.ColumnCount(); ++i) present[names.ColumnName(i)] = true;
  }
  std::string sql;
  const auto select = [&](const std::string& column) {
    index_[column] = static_cast<int>(index_.size());
    sql += (sql.empty() ? "SELECT " : ", ") + Quoted(column);
  };
  for (const std::string& column : required) {
    if (!present.count(column)) {
      throw InputError(db.path() + ": table " + table + " has no column " + column);
    }
    select(column);
  }
  for (const std::string& column : optional) {
    if (present.count(column)) select(column);
  }
  stmt_ = std::make_unique<SqliteStatement>(db, sql + " FROM " + Quoted(table));
}

TableReader::~TableReader() = default;

bool TableReader::Next() {
  if (!stmt_->Step()) return false;
  ++row_;
  return true;
}

std::string TableReader::Where(const std::string& column) const {
  return db_.path() + ": " + table_ + " row " + std::to_string(row_) + ": " + column;
}

void TableReader::Refuse(const std::string& column, const std::string& what) const {
  throw InputError(Where(column) + " " + what);
}

int TableReader::Index(const std::string& column) const {
  const auto it = index_.find(column);
  if (it == index_.end()) throw std::logic_error("TableReader: column not selected: " + column);
  return it->second;
}

bool TableReader::IsNull(const std::string& column) const { return stmt_->IsNull(Index(column)); }

std::int64_t TableReader::Integer(const std::string& column, std::int64_t lo,
                                  std::int64_t hi) const {
  const int i = Index(column);
  if (stmt_->IsNull(i)) Refuse(column, "is NULL");
  if (!stmt_->IsInteger(i))
    Refuse(column, "is not an integer ('" + stmt_->Text(i).substr(0, 40) + "')");
  const std::int64_t v = stmt_->Int(i);
  if (v < lo || v > hi) {
    Refuse(column, std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "]");
  }
  return v;
}

int TableReader::Id(const std::string& column) const {
  return static_cast<int>(Integer(column, 0, INT_MAX));
}

bool TableReader::Flag(const std::string& column) const { return Integer(column, 0, 1) != 0; }

double TableReader::RealOrNaN(const std::string& column, double lo, double hi) const {
  const int i = Index(column);
  if (stmt_->IsNull(i)) return std::nan("");
  if (!stmt_->IsInteger(i) && !stmt_->IsReal(i)) {
    Refuse(column, "is not a number ('" + stmt_->Text(i).substr(0, 40) + "')");
  }
  const double v = stmt_->Double(i);
  if (!std::isfinite(v)) Refuse(column, Num(v) + " is not finite");
  if (v < lo || v > hi) Refuse(column, Num(v) + " is outside [" + Num(lo) + ", " + Num(hi) + "]");
  return v;
}

double TableReader::Real(const std::string& column, double lo, double hi) const {
  if (stmt_->IsNull(Index(column))) Refuse(column, "is NULL");
  return RealOrNaN(column, lo, hi);
}

std::string TableReader::Text(const std::string& column, bool required) const {
  const int i = Index(column);
  if (stmt_->IsNull(i)) {
    if (required) Refuse(column, "is NULL");
    return "";
  }
  return stmt_->Text(i);
}

std::vector<unsigned char> TableReader::Blob(const std::string& column,
                                             const std::string& owner) const {
  const int i = Index(column);
  if (stmt_->IsNull(i)) Refuse(column, "is NULL");
  if (!stmt_->IsBlob(i)) Refuse(column, "is not a blob");
  std::vector<unsigned char> blob = stmt_->Blob(i);
  const std::string checksum = ChecksumColumn(column);
  if (Has(checksum) && Integer(checksum, INT64_MIN, INT64_MAX) != BlobChecksum(blob)) {
    Refuse(column, (owner.empty() ? "" : "of " + owner + " ") + "does not match its checksum " +
                       checksum + ": the blob is damaged");
  }
  return blob;
}

}  // namespace uwbsar::session
