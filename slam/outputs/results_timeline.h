// What each command puts into results.mcap (slam/outputs/results_mcap.h), in time order:
// - a mapping run (`map`, `demo`): at the first odometry stamp the ground truth
//   (/ground_truth/path); after each solve (SlamSnapshot::solves) the navigation grid (/map),
//   the corrected path (/path) and the accepted loops and keyframes (/uwbsar/loops) as they
//   were then, so the last /map is map.pgm; /tf every tf_period_s of odometry (odom ->
//   base_link the odometry, map -> odom the final correction, so the robot follows the final
//   /path); at the last stamp the SAR mosaic.
// - a session of several runs (`map --resume`, `merge`): the final map and mosaic at the newest
//   run's first stamp, every run's path (/uwbsar/run_<id>/path; /path is the newest run),
//   the loops, and /tf over the newest run.
// - `localize`: the saved map (its map.pgm) and mosaic at the first stamp, /tf from the
//   localisation's correction, and the trajectory in the map frame (/path) at the end.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "imaging/occupancy_grid.h"
#include "slam/app_config.h"
#include "slam/localization/localize_job.h"
#include "slam/outputs/results_mcap.h"
#include "slam/session/session_data.h"
#include "slam/slam_snapshot.h"

namespace uwbsar::slam {

/// The file name in an output folder.
inline constexpr const char* kResultsMcapName = "results.mcap";
/// /tf is written at most this often (odometry time).
inline constexpr double kResultsTfPeriodS = 0.1;
/// /path keeps a pose every this much odometry path (and the last one).
inline constexpr double kResultsPathSpacingM = 0.05;

/// A mapping run; `ground_truth` may be empty.
void WriteRunResultsMcap(const std::string& path, const SlamSnapshot& slam,
                         const std::vector<OdometrySample>& ground_truth, const SarMosaic& sar);

/// A session of several runs; `grid` its navigation grid (map.pgm), `ground_truth` by run.
void WriteSessionResultsMcap(const std::string& path, const SessionData& session,
                             const Config& config, const OccupancyGrid& grid, const SarMosaic& sar,
                             const std::map<int, std::vector<OdometrySample>>& ground_truth);

/// A localisation run in the saved map `map`, whose navigation grid (its map.pgm) is `map_grid`.
void WriteLocalizeResultsMcap(const std::string& path, const LocalizeRun& run,
                              const SessionData& map, const Config& config,
                              const OccupancyGrid& map_grid);

}  // namespace uwbsar::slam
