// Everything `uwbsar map` leaves in its output folder (README "uwbsar map"):
// map.png, map_float.tif + map_grid.yaml, map.pgm + map.yaml, trajectory.tum,
// odometry.tum, graph.g2o, loops.csv, summary.json and report.html.
// All files (the exact map too) are first written into a hidden staging folder
// inside DIR and renamed into place at the end, summary.json last: a folder with
// a summary.json holds one complete result, and a failed run leaves none.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "frontend/place_recognition/detector_kind.h"
#include "slam/map_job.h"
#include "slam/outputs/map_output_stage.h"

namespace uwbsar::slam {

/// The state of `run` now. Hold run.slam->LockState() while its keyframe thread may run.
MapState CaptureMapState(const MapRun& run);

/// An ATE as summary.json holds it, everywhere (docs/formats.md): poses, rmse_m, mean_m,
/// max_m, yaw_rmse_deg.
nlohmann::json AteJson(const AteResult& ate);

/// Writes every output of `run` but summary.json into `stage_dir` (trajectories, graph, loops,
/// the global map and navigation grid, results.mcap when asked, report.html, and the exact map
/// of `exact_from` when given), the map drawn through `mosaic` when given. Appends the names
/// written to `names`, in MapOutputs::files' order; returns the outputs with their summary.
/// MapOutputStage commits them.
MapOutputs WriteMapFiles(const MapState& run, const std::string& stage_dir,
                         const MapRun* exact_from, IncrementalMosaic* mosaic,
                         std::vector<std::string>* names);

/// trajectory.tum moved onto ground_truth.tum by the ATE's alignment (written with an ATE).
inline constexpr const char* kAlignedTrajectoryName = "trajectory_aligned.tum";

/// The exact global map: every imaged scan back-projected again at its corrected pose
/// (the keyframe correction interpolated in time and applied to its odometry pose), at the
/// imaging resolution: map_exact_float.tif (raw values), map_exact_grid.yaml and
/// map_exact.png (the paper's enhancement). Returns the files written. Needs the run mapped
/// with slam.keep_scan_profiles (std::logic_error otherwise).
std::vector<std::string> WriteExactMap(const MapRun& run, const std::string& out_dir);

/// loops.csv's header (no newline): query_id,match_id, ratio_, good_ and scale_ of each of
/// `detectors` (named after it), x_m,y_m,yaw_deg,validator,reason,backend,chi2.
std::string LoopsCsvHeader(const std::vector<DetectorKind>& detectors);

/// The text of a *_grid.yaml: the pixel geometry of the float map `image` (what `uwbsar
/// compare` reads), with a comment naming `what` it describes and the `frame` of x, y.
std::string GridYaml(const ImageGrid& grid, const std::string& what, const std::string& image,
                     const std::string& frame = "world");

}  // namespace uwbsar::slam
