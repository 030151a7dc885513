#include "drivers/logs/tum_reader.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/bounded_file.h"
#include "core/stamp_range.h"

namespace uwbsar {

std::vector<OdometrySample> ReadTum(const std::string& path, double max_mb,
                                    std::vector<int>* lines) {
  std::ifstream in = OpenTextInput(path, "trajectory", max_mb);
  std::vector<OdometrySample> out;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    double v[8];
    int n = 0;
    while (n < 8 && fields >> v[n]) ++n;
    if (n == 0 && fields.eof()) continue;  // blank line
    std::string extra;
    if (n != 8 || (fields >> extra)) {
      throw InputError(path + ":" + std::to_string(line_no) +
                       ": expected 8 numbers 't x y z qx qy qz qw'");
    }
    for (double x : v) {
      if (!std::isfinite(x)) {
        throw InputError(path + ":" + std::to_string(line_no) + ": non-finite value");
      }
    }
    // Compared in seconds first: SecondsToNs of 1e30 s would overflow.
    if (!(std::abs(v[0]) < 1e10) || !IsOutputStamp(SecondsToNs(v[0]))) {
      std::ostringstream what;
      what.precision(12);
      what << path << ":" << line_no << ": stamp " << v[0] << " s is outside "
           << OutputStampRange();
      throw InputError(what.str());
    }
    OdometrySample s;
    s.stamp_ns = SecondsToNs(v[0]);
    s.T_world_robot.x_m = v[1];
    s.T_world_robot.y_m = v[2];
    const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
    s.T_world_robot.yaw_rad =
        std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    out.push_back(s);
    if (lines != nullptr) lines->push_back(line_no);
  }
  if (out.empty()) throw InputError(path + ": no poses in trajectory file");
  return out;
}

}  // namespace uwbsar
