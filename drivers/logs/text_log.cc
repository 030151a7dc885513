#include "drivers/logs/text_log.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/bounded_file.h"

namespace uwbsar {
namespace {

/// One whitespace-separated field, parsed whole ("12abc" is not 12).
template <class T>
T Field(std::istringstream& in, const std::string& where, const char* name) {
  std::string token;
  if (!(in >> token)) throw InputError(where + ": missing field '" + name + "'");
  std::istringstream parse(token);
  T value{};
  if (!(parse >> value) || parse.peek() != std::char_traits<char>::eof()) {
    throw InputError(where + ": field '" + name + "' has invalid value '" + token + "'");
  }
  return value;
}

/// A record ends with its last field: anything after it makes the line malformed.
void ExpectEnd(std::istringstream& in, const std::string& where, const char* record) {
  std::string extra;
  if (in >> extra) {
    throw InputError(where + ": unexpected '" + extra + "' after the last field of the " + record +
                     " record");
  }
}

}  // namespace

TextLog ReadTextLog(const std::string& path, double max_mb) {
  std::ifstream file = OpenTextInput(path, "log", max_mb);
  TextLog log;
  std::string line;
  for (int line_no = 1; std::getline(file, line); ++line_no) {
    const std::string where = path + ":" + std::to_string(line_no);
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream in(line);
    std::string kind;
    if (!(in >> kind)) continue;
    if (kind == "odom") {
      OdometrySample s;
      s.stamp_ns = Field<TimestampNs>(in, where, "stamp_ns");
      s.T_world_robot.x_m = Field<double>(in, where, "x_m");
      s.T_world_robot.y_m = Field<double>(in, where, "y_m");
      s.T_world_robot.yaw_rad = Field<double>(in, where, "yaw_rad");
      ExpectEnd(in, where, "odom");
      log.odometry.push_back(s);
    } else if (kind == "scan") {
      RadarScan s;
      s.stamp_ns = Field<TimestampNs>(in, where, "stamp_ns");
      s.sensor_id = Field<int>(in, where, "sensor_id");
      const long n = Field<long>(in, where, "n");
      if (n < 0 || n > 1'000'000) throw InputError(where + ": field 'n' out of range");
      s.samples.resize(static_cast<std::size_t>(n));
      for (float& v : s.samples) {
        // Read as text so that "nan"/"inf" reach the frontend, which rejects and counts them.
        std::string token;
        if (!(in >> token)) throw InputError(where + ": fewer samples than n=" + std::to_string(n));
        char* end = nullptr;
        v = std::strtof(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0') {
          throw InputError(where + ": sample '" + token + "' is not a number");
        }
      }
      std::string extra;
      if (in >> extra) throw InputError(where + ": more samples than n=" + std::to_string(n));
      log.scans.push_back(std::move(s));
    } else {
      throw InputError(where + ": unknown record '" + kind + "' (expected odom or scan)");
    }
  }
  auto by_time = [](const auto& a, const auto& b) { return a.stamp_ns < b.stamp_ns; };
  std::stable_sort(log.odometry.begin(), log.odometry.end(), by_time);
  std::stable_sort(log.scans.begin(), log.scans.end(), by_time);
  return log;
}

void WriteTextLog(const std::string& path, const TextLog& log) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << "# uwbsar text log: odom <stamp_ns> <x_m> <y_m> <yaw_rad> | "
           "scan <stamp_ns> <sensor_id> <n> <samples...>\n";
    char buf[64];
    for (const OdometrySample& s : log.odometry) {
      std::snprintf(buf, sizeof(buf), "%.9g %.9g %.9g", s.T_world_robot.x_m, s.T_world_robot.y_m,
                    s.T_world_robot.yaw_rad);
      out << "odom " << s.stamp_ns << " " << buf << "\n";
    }
    for (const RadarScan& s : log.scans) {
      out << "scan " << s.stamp_ns << " " << s.sensor_id << " " << s.samples.size();
      for (float v : s.samples) {
        std::snprintf(buf, sizeof(buf), " %.9g", static_cast<double>(v));
        out << buf;
      }
      out << "\n";
    }
    if (!out.flush()) {
      const int error = errno;
      out.close();
      std::remove(tmp.c_str());
      throw std::runtime_error(path + ": cannot write: " + std::strerror(error));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": cannot rename temporary file into place");
  }
}

}  // namespace uwbsar
