// The parts of summary.json that every output folder shares (docs/formats.md, "summary.json"):
// a single run's (slam/outputs/map_outputs.h), a joined map's (slam/outputs/session_outputs.h) and
// a localisation's (slam/localization/localize_job.h) are made by the same functions, so that one
// key means one thing in every folder.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>

#include "backend/backend_config.h"
#include "backend/pose_graph.h"
#include "frontend/imaging_frontend.h"
#include "imaging/image_grid.h"
#include "slam/slam_snapshot.h"

namespace uwbsar::slam {

/// What the command that wrote the folder read and did: a map run, `map --resume` (the new
/// run and the join), `merge` (the join alone: no log read) or `localize`.
struct CommandWork {
  double log_duration_s = 0.0;  ///< seconds of log read
  double processing_s = 0.0;    ///< seconds of work
  FrontendStats frontend;       ///< scans and odometry read
  StageTimes times;             ///< per stage
  bool stages_timed = true;     ///< false: time_s holds the total alone (the stages null)
  int solves = 0;               ///< pose-graph solves
  OptimizeResult optimization;  ///< the last solve
};

/// log_duration_s, processing_s, real_time_factor, peak_memory_mib, scans, odometry, time_s
/// and optimization of `work`, added to `summary`.
void AddCommandWork(const CommandWork& work, nlohmann::json* summary);

/// `odometry_calibration`: the base calibration applied (all 0: uncalibrated).
nlohmann::json OdometryCalibrationJson(const BackendConfig& backend);

/// `map`: the global map's grid, its blocks of the sparse canvas and their memory.
nlohmann::json MapExtentJson(const ImageGrid& grid, std::size_t blocks, std::size_t memory_bytes);

}  // namespace uwbsar::slam
