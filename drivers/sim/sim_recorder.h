// Consumers of a SimStream: collect it in memory, and write the files a
// simulated run produces besides the bag: ground_truth.tum (TUM trajectory,
// `t x y z qx qy qz qw`, seconds, readable by evo) and the project's plain text
// log of odometry and radar scans (drivers/logs/text_log.h).
#pragma once

#include <string>
#include <vector>

#include "drivers/logs/text_log.h"
#include "drivers/sim/sim_stream.h"

namespace uwbsar::sim {

/// A whole simulated run in memory, each list in time order.
struct SimRecording {
  std::vector<OdometrySample> ground_truth;
  std::vector<OdometrySample> odometry;
  std::vector<RadarScan> scans;  ///< all radars
  std::vector<SimLaserScan> laser;
};

/// Drains `stream` into memory.
SimRecording RecordStream(SimStream* stream);

/// Writes poses as a TUM trajectory, atomically (temporary name, then rename).
/// Throws InputError if the file cannot be written.
void WriteTumTrajectory(const std::string& path, const std::vector<OdometrySample>& poses);
/// Formats one TUM line (no newline): stamp in seconds with nanosecond digits.
std::string TumLine(const OdometrySample& pose);

/// The recording's odometry and scans as a text log (ground truth and laser are not part
/// of that format).
TextLog ToTextLog(const SimRecording& recording);

}  // namespace uwbsar::sim
