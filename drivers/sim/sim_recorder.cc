#include "drivers/sim/sim_recorder.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/errors.h"

namespace uwbsar::sim {

SimRecording RecordStream(SimStream* stream) {
  SimRecording rec;
  SimMessage msg;
  while (stream->Next(&msg)) {
    switch (msg.kind) {
      case SimMessage::Kind::kGroundTruth:
        rec.ground_truth.push_back(msg.pose);
        break;
      case SimMessage::Kind::kOdometry:
        rec.odometry.push_back(msg.pose);
        break;
      case SimMessage::Kind::kRadarScan:
        rec.scans.push_back(std::move(msg.scan));
        break;
      case SimMessage::Kind::kLaserScan:
        rec.laser.push_back(std::move(msg.laser));
        break;
    }
  }
  return rec;
}

std::string TumLine(const OdometrySample& pose) {
  // Integer seconds and nanoseconds printed separately: exact whatever the epoch.
  const TimestampNs ns = pose.stamp_ns;
  const std::int64_t sec = ns >= 0 ? ns / 1'000'000'000 : -((-ns + 999'999'999) / 1'000'000'000);
  const std::int64_t frac = ns - sec * 1'000'000'000;
  const double half = 0.5 * pose.T_world_robot.yaw_rad;
  char line[160];
  std::snprintf(line, sizeof(line), "%" PRId64 ".%09" PRId64 " %.6f %.6f 0 0 0 %.9f %.9f", sec,
                frac, pose.T_world_robot.x_m, pose.T_world_robot.y_m, std::sin(half),
                std::cos(half));
  return line;
}

void WriteTumTrajectory(const std::string& path, const std::vector<OdometrySample>& poses) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw InputError(path + ": cannot write trajectory");
    out << "# timestamp x y z qx qy qz qw\n";
    for (const OdometrySample& p : poses) out << TumLine(p) << "\n";
    if (!out.flush()) throw InputError(path + ": cannot write trajectory");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw InputError(path + ": cannot write trajectory: " + ec.message());
}

TextLog ToTextLog(const SimRecording& recording) {
  TextLog log;
  log.odometry = recording.odometry;
  log.scans = recording.scans;
  return log;
}

}  // namespace uwbsar::sim
