// The staging of an output folder's files (`uwbsar map`, `localize`, a joined session, live
// snapshots): a hidden staging folder inside DIR made before the work under DIR's lock, the
// outputs written into it (slam/outputs/map_outputs.h WriteMapFiles) and published into DIR as
// one set, summary.json last (core/commit_journal.h); the completion of a commit a dead process
// left, the removal of staging folders left by dead processes, and removal on Ctrl-C.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "backend/trajectory_metrics.h"
#include "core/folder_lock.h"
#include "core/interrupt_cleanup.h"
#include "slam/map_job.h"
#include "slam/slam_snapshot.h"

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

}  // namespace uwbsar::slam
