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

#include "core/folder_lock.h"
#include "core/interrupt_cleanup.h"
#include "frontend/place_recognition/detector_kind.h"
#include "slam/map_job.h"

namespace uwbsar {
class IncrementalMosaic;
}

namespace uwbsar::slam {

struct MapOutputs {
  std::vector<std::string> files;  ///< final paths written
  nlohmann::json summary;          ///< the content of summary.json
  AteResult ate;                   ///< of trajectory.tum (num_poses 0 without ground truth)
  AteResult odometry_ate;          ///< of odometry.tum
};

/// What the outputs are made from: a copy of a run's SLAM state and its run-level fields.
/// Taken in time linear in keyframes, loops and odometry (no rendering, no I/O), so a live
/// writer holds the SLAM state lock only for CaptureMapState and writes without it.
struct MapState {
  SlamSnapshot slam;
  std::string input;
  double processing_s = 0.0;
  double log_duration_s = 0.0;  ///< MapRun::log_duration_s() at capture
  TimestampNs last_stamp_ns = 0;
  std::vector<OdometrySample> ground_truth;
};

/// The state of `run` now. Hold run.slam->LockState() while its keyframe thread may run.
MapState CaptureMapState(const MapRun& run);

/// An ATE as summary.json holds it, everywhere (docs/formats.md): poses, rmse_m, mean_m,
/// max_m, yaw_rmse_deg.
nlohmann::json AteJson(const AteResult& ate);

struct MapOutputOptions {
  bool exact = false;  ///< also the exact map (WriteExactMap), staged and committed with the rest
};

/// The hidden staging folder of one run inside DIR (`.uwbsar-partial-<pid>`). Created before
/// the work starts (it proves DIR writable), under DIR's exclusive lock (LockOutputFolder),
/// held until the stage is destroyed; Ctrl-C removes it (core/interrupt_cleanup.h), as does
/// the destructor. Commit writes every output into it and publishes them into DIR as one set
/// (core/commit_journal.h), summary.json last, removing the outputs of an earlier run that
/// this run does not write: a committed folder holds exactly one run's files, and a commit
/// interrupted at any point is completed by the next command that locks DIR.
class MapOutputStage {
 public:
  /// Throws InputError naming DIR when it cannot be created or written.
  explicit MapOutputStage(const std::string& out_dir);
  ~MapOutputStage();
  MapOutputStage(const MapOutputStage&) = delete;
  MapOutputStage& operator=(const MapOutputStage&) = delete;

  const std::string& path() const { return stage_; }
  /// More files for the next commits: `write(stage_dir)` writes them into the staging
  /// folder and returns their names, committed with the rest (e.g. session.uwbsar).
  using ExtraOutputs = std::function<std::vector<std::string>(const std::string& stage_dir)>;
  void SetExtraOutputs(ExtraOutputs write) { extra_outputs_ = std::move(write); }
  /// The global map of the next commits is `mosaic`, brought up to date (only what changed
  /// since its last update is redrawn); owned by the caller, who keeps it between stages
  /// (live snapshots). Without it each commit renders the map from every tile.
  void KeepMosaic(IncrementalMosaic* mosaic) { mosaic_ = mosaic; }
  /// CaptureMapState(run), then the outputs from it (and the exact map from `run`).
  MapOutputs Commit(const MapRun& run, const MapOutputOptions& options = {});
  /// The outputs of a captured state (no exact map: that needs the scans' profiles).
  MapOutputs Commit(const MapState& state);
  /// Commits, as one set like Commit, the files `write(stage_dir)` writes into the staging
  /// folder: it returns their names and writes summary.json last (e.g. a joined session's
  /// outputs, `map --resume`). When `write` throws nothing in DIR is changed. Returns the
  /// committed paths, summary.json last.
  std::vector<std::string> CommitWritten(const ExtraOutputs& write);

 private:
  MapOutputs CommitState(const MapState& state, const MapRun* exact_from);

  std::string out_dir_, stage_;
  bool created_dir_ = false;  ///< out_dir did not exist: a run that fails removes it again
  FolderLock lock_;
  std::unique_ptr<RemoveOnInterrupt> guard_;
  ExtraOutputs extra_outputs_;
  IncrementalMosaic* mosaic_ = nullptr;
};

/// trajectory.tum moved onto ground_truth.tum by the ATE's alignment (written with an ATE).
inline constexpr const char* kAlignedTrajectoryName = "trajectory_aligned.tum";

/// Every file name a uwbsar command may commit into an output folder (map, joined session,
/// localize, live), but the per-run trajectory_<run>.tum and ground_truth_<run>.tum of a joined
/// session.
const std::vector<std::string>& AllMapOutputNames();

/// The outputs of earlier runs in `out_dir` (AllMapOutputNames and the per-run files) that
/// are not in `names`: a commit of `names` removes them.
std::vector<std::string> EarlierOutputsNotIn(const std::string& out_dir,
                                             const std::vector<std::string>& names);

/// Creates `out_dir` when missing and locks it exclusively for this process (refused with one
/// line naming the holder when another process writes or reads it), completes a commit that a
/// dead process left in it and removes dead processes' staging folders. Every command that
/// writes an output folder holds this for its whole run.
FolderLock LockOutputFolder(const std::string& out_dir);

/// MapOutputStage(out_dir).Commit(run, options).
MapOutputs WriteMapOutputs(const MapRun& run, const std::string& out_dir,
                           const MapOutputOptions& options = {});
/// MapOutputStage(out_dir).Commit(state).
MapOutputs WriteMapOutputs(const MapState& state, const std::string& out_dir);

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
