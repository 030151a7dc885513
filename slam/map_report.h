// report.html of `uwbsar map` (map_outputs.h): the page's content built from a captured
// run, the trajectories and loop counts already written, and the staged map.png.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "slam/map_outputs.h"
#include "slam/report_html.h"

namespace uwbsar::slam {

/// A trajectory as written to the TUM files, stamps in nanoseconds.
using StampedPoses = std::vector<std::pair<TimestampNs, Pose2>>;

/// The trajectories of one run's outputs: corrected SLAM, odometry, and ground truth (empty
/// when the run has none).
struct MapTrajectories {
  StampedPoses slam;
  StampedPoses odometry;
  StampedPoses ground_truth;
};

/// The loop candidates of a run counted by outcome.
struct LoopCounts {
  int validated = 0;         ///< accepted by the validator
  int accepted = 0;          ///< in the graph now
  int backend_rejected = 0;  ///< validated, then switched off by the backend
};
LoopCounts CountLoops(const SlamSnapshot& slam);

/// The report of `state`: key figures (with `outputs`' ATEs when it has them), map.png
/// (`map_png` holds the file's bytes), the trajectories, timing and loop tables.
RunReport BuildMapReport(const MapState& state, const MapOutputs& outputs,
                         const MapTrajectories& trajectories, const std::string& map_png);

/// `v` with `digits` digits after the point (as the report and loops.csv print numbers).
std::string Fixed(double v, int digits);

}  // namespace uwbsar::slam
