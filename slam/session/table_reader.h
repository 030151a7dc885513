// Reading one table of the session file by column name, every value range-checked: the
// columns are looked up by name (their order in the file does not matter; extra columns are
// ignored), a missing one is refused naming it, and each read refuses NULL where a value is
// required, the wrong storage class (text where a number belongs) and values outside the
// range the caller gives. Every refusal is one InputError line
// "<file>: <table> row <n>: <column> <what is wrong>", n counting the rows from 1 in the order
// `SELECT * FROM <table>` lists them. A blob is checked against its checksum column when
// the caller selects it (format version 8), before anything decodes it.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "slam/session/sqlite_db.h"

namespace uwbsar::session {

class TableReader {
 public:
  /// Selects `required` (each must exist: else InputError "<file>: table <table> has no column
  /// <name>") and those of `optional` that exist; a missing table is refused the same way.
  TableReader(SqliteDb& db, const std::string& table, const std::vector<std::string>& required,
              const std::vector<std::string>& optional = {});
  ~TableReader();

  /// Steps to the next row: false when done.
  bool Next();
  std::int64_t row() const { return row_; }
  bool Has(const std::string& column) const { return index_.count(column) != 0; }

  /// "<file>: <table> row <n>: <column>", the start of every refusal of that value.
  std::string Where(const std::string& column) const;
  /// Throws InputError "Where(column) <what>".
  [[noreturn]] void Refuse(const std::string& column, const std::string& what) const;

  bool IsNull(const std::string& column) const;
  /// An integer (not NULL, not text or real) within [lo, hi].
  std::int64_t Integer(const std::string& column, std::int64_t lo, std::int64_t hi) const;
  /// An id: an integer within [0, INT_MAX] (read as 64-bit, so larger ones are refused, not
  /// wrapped).
  int Id(const std::string& column) const;
  /// 0 or 1.
  bool Flag(const std::string& column) const;
  /// A number (integer or real, not NULL), finite and within [lo, hi].
  double Real(const std::string& column, double lo, double hi) const;
  /// The same, NULL read as NaN (columns where NaN is a meaning, stored as NULL).
  double RealOrNaN(const std::string& column, double lo, double hi) const;
  /// Text; NULL is refused with `required`, else read as "".
  std::string Text(const std::string& column, bool required = true) const;
  /// A blob (NULL or another storage class refused). When its checksum column
  /// (blob_checksum.h, `<column>_xxh3`) is selected, the blob must match it: else refused as
  /// damaged, naming `owner` (e.g. "keyframe 12") after the column.
  std::vector<unsigned char> Blob(const std::string& column, const std::string& owner = "") const;

 private:
  int Index(const std::string& column) const;

  SqliteDb& db_;
  std::string table_;
  std::map<std::string, int> index_;
  std::unique_ptr<SqliteStatement> stmt_;
  std::int64_t row_ = 0;
};

}  // namespace uwbsar::session
