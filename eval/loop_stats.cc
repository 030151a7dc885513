#include "eval/loop_stats.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/bounded_file.h"
#include "core/errors.h"

namespace uwbsar {
namespace {

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::stringstream in(line);
  while (std::getline(in, field, ',')) {
    const auto b = field.find_first_not_of(" \t\r");
    const auto e = field.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

struct Cursor {
  const std::string& source;
  int line;
  std::string Where(const std::string& column) const {
    return source + ":" + std::to_string(line) + ": column '" + column + "'";
  }
};

double ParseDouble(const std::string& text, const Cursor& at, const std::string& column) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE) {
    throw InputError(at.Where(column) + ": '" + text + "' is not a number");
  }
  return v;
}

int ParseInt(const std::string& text, const Cursor& at, const std::string& column) {
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || v < 0 ||
      v > 1000000000L) {
    throw InputError(at.Where(column) + ": '" + text + "' is not a count or index >= 0");
  }
  return static_cast<int>(v);
}

}  // namespace

std::vector<std::string> PairStatsColumns(const std::vector<DetectorKind>& detectors) {
  std::vector<std::string> columns = {"d", "r"};
  for (DetectorKind kind : detectors) {
    const std::string n = DetectorColumnName(kind);
    for (const std::string& c :
         {"n_" + n, "scale_" + n, "tx_" + n + "_px", "ty_" + n + "_px", "rot_" + n + "_deg"}) {
      columns.push_back(c);
    }
  }
  return columns;
}

std::vector<PairStats> ParsePairStats(const std::string& csv_text, const std::string& source,
                                      const std::vector<DetectorKind>& detectors) {
  std::stringstream in(csv_text);
  std::string line;
  int line_no = 0;
  std::map<std::string, std::size_t> column;
  std::vector<PairStats> out;
  std::set<std::pair<int, int>> seen;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const std::vector<std::string> fields = SplitCsv(line);
    if (column.empty()) {
      for (std::size_t k = 0; k < fields.size(); ++k) column[fields[k]] = k;
      for (const std::string& name : PairStatsColumns(detectors)) {
        if (!column.count(name)) {
          throw InputError(source + ":" + std::to_string(line_no) + ": header lacks column '" +
                           name + "'");
        }
      }
      continue;
    }
    const Cursor at{source, line_no};
    auto field = [&](const std::string& name) -> const std::string& {
      const std::size_t k = column.at(name);
      if (k >= fields.size()) throw InputError(at.Where(name) + ": missing field");
      return fields[k];
    };
    auto detector = [&](const std::string& suffix) {
      DetectorStats s;
      s.good_matches = ParseInt(field("n_" + suffix), at, "n_" + suffix);
      const std::string names[4] = {"scale_" + suffix, "tx_" + suffix + "_px",
                                    "ty_" + suffix + "_px", "rot_" + suffix + "_deg"};
      int missing = 0;
      for (const std::string& n : names) missing += field(n).empty() || field(n) == "-";
      if (missing == 4) return s;  // no transform
      if (missing != 0) throw InputError(at.Where(names[0]) + ": transform is only partly given");
      s.has_transform = true;
      s.scale = ParseDouble(field(names[0]), at, names[0]);
      s.tx_px = ParseDouble(field(names[1]), at, names[1]);
      s.ty_px = ParseDouble(field(names[2]), at, names[2]);
      s.rotation_deg = ParseDouble(field(names[3]), at, names[3]);
      return s;
    };
    PairStats p;
    p.d = ParseInt(field("d"), at, "d");
    p.r = ParseInt(field("r"), at, "r");
    for (DetectorKind kind : detectors) p.detectors[kind] = detector(DetectorColumnName(kind));
    if (!seen.insert({p.d, p.r}).second) {
      throw InputError(at.Where("d") + ": pair (" + std::to_string(p.d) + ", " +
                       std::to_string(p.r) + ") is listed twice");
    }
    out.push_back(p);
  }
  if (column.empty()) throw InputError(source + ": no header line");
  return out;
}

std::vector<PairStats> ReadPairStatsFile(const std::string& path,
                                         const std::vector<DetectorKind>& detectors,
                                         double max_mb) {
  std::ifstream in = OpenTextInput(path, "statistics", max_mb);
  std::stringstream text;
  text << in.rdbuf();
  return ParsePairStats(text.str(), path, detectors);
}

std::string PairStatsRow(const PairStats& p, const std::vector<DetectorKind>& detectors) {
  auto det = [](const DetectorStats& s) {
    char buf[160];
    if (!s.has_transform) {
      std::snprintf(buf, sizeof(buf), "%d,-,-,-,-", s.good_matches);
    } else {
      std::snprintf(buf, sizeof(buf), "%d,%.6g,%.6g,%.6g,%.6g", s.good_matches, s.scale, s.tx_px,
                    s.ty_px, s.rotation_deg);
    }
    return std::string(buf);
  };
  std::string row = std::to_string(p.d) + "," + std::to_string(p.r);
  for (DetectorKind kind : detectors) row += "," + det(Of(p.detectors, kind, DetectorStats()));
  return row;
}

LoopMatrix EvaluateLoopMatrix(const std::vector<PairStats>& stats,
                              const LoopValidationConfig& config) {
  LoopMatrix m;
  std::set<int> ds, rs;
  for (const PairStats& p : stats) {
    ds.insert(p.d);
    rs.insert(p.r);
  }
  m.d_ids.assign(ds.begin(), ds.end());
  m.r_ids.assign(rs.begin(), rs.end());
  m.loops.assign(m.d_ids.size(), std::vector<int>(m.r_ids.size(), 0));
  m.reasons.assign(m.d_ids.size(), std::vector<std::string>(m.r_ids.size()));
  auto index = [](const std::vector<int>& ids, int v) {
    return static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin());
  };
  for (const PairStats& p : stats) {
    const DetectorStats none;
    const LoopDecision d = ApplyLoopRule(Of(p.detectors, config.detectors[0], none),
                                         Of(p.detectors, config.detectors[1], none), config);
    const std::size_t i = index(m.d_ids, p.d), j = index(m.r_ids, p.r);
    m.loops[i][j] = d.accepted ? 1 : 0;
    m.reasons[i][j] = d.reason;
  }
  return m;
}

}  // namespace uwbsar
