// Everything `uwbsar map` leaves in its output folder (README "uwbsar map"):
// map.png, map_float.tif + map_grid.yaml, map.pgm + map.yaml, trajectory.tum,
// odometry.tum, graph.g2o, loops.csv, summary.json and report.html.
// All files are first written into a hidden staging folder inside DIR and
// renamed into place at the end, summary.json last: a folder with a
// summary.json holds a complete result, and a failed run leaves none.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/map_job.h"

namespace uwbsar::tools {

struct MapOutputs {
  std::vector<std::string> files;  ///< final paths written
  nlohmann::json summary;          ///< the content of summary.json
  AteResult ate;                   ///< of trajectory.tum (num_poses 0 without ground truth)
  AteResult odometry_ate;          ///< of odometry.tum
};

MapOutputs WriteMapOutputs(const MapRun& run, const std::string& out_dir);

/// The exact global map: every imaged scan back-projected again at its corrected pose
/// (the keyframe correction interpolated in time and applied to its odometry pose), at the
/// imaging resolution: map_exact_float.tif (raw values), map_exact_grid.yaml and
/// map_exact.png (the paper's enhancement). Returns the files written. Needs the run mapped
/// with slam.keep_scan_profiles (std::logic_error otherwise).
std::vector<std::string> WriteExactMap(const MapRun& run, const std::string& out_dir);

/// The five-line summary printed by `uwbsar map` and `uwbsar demo`.
void PrintMapSummary(const MapRun& run, const MapOutputs& outputs, const std::string& out_dir);

}  // namespace uwbsar::tools
