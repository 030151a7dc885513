// SlamSystem: the whole pipeline behind one object, the same for offline logs
// and live drivers (docs/architecture.md): scans and odometry go in; the
// imaging frontend closes keyframe tiles; each new keyframe gets its AKAZE and
// ORB features once, is matched against candidate keyframes near its pose
// estimate, validated loops go into the Ceres pose graph, which is re-solved
// incrementally after accepted loops. Outputs are read from the accessors.
//
// Threading: Add*/Finish are called from one thread (the feeding thread), which runs
// the imaging frontend. With slam.keyframe_thread, each closed keyframe (with the
// odometry that came before it) is handed through a bounded FIFO to a worker thread
// that does the keyframe work: features, matching, graph edges and solves. The
// frontend never reads the graph, and the worker takes keyframes in order, so the
// result is the same as with everything on the feeding thread: the same input always
// gives the same result. Only the feeding thread's latency changes (live mode).
//
// Reading results: the accessors returning references (keyframes, loops, odometry,
// graph, last_optimization, KeyframePoses, Corrected*) read the worker's state. Read
// them after Finish(), after WaitIdle() on the feeding thread, or from any thread
// while holding LockState() (e.g. a live snapshot writer). frontend_stats() and
// times() return copies and may be called from any thread at any time.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "backend/gyro_stillness.h"
#include "backend/pose_graph.h"
#include "frontend/imaging_frontend.h"
#include "frontend/keyframe_products.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "slam/app_config.h"
#include "slam/ordered_worker.h"
#include "slam/session/tile_store.h"
#include "slam/slam_snapshot.h"
#include "slam/wall_edges.h"
#include "slam/wall_landmarks.h"

namespace uwbsar::slam {

/// A keyframe as SLAM keeps it (its features live in the PlaceRecognizer).
struct KeyframeRecord {
  Keyframe keyframe;        ///< tile image dropped after use unless slam.keep_tile_images
  TileRef detected;         ///< detected tile (positive / magnitude, blurred) at map resolution,
                            ///< in the tile cache file (slam/session/tile_store.h)
  ImageGrid detected_grid;  ///< its geometry in the anchor frame
};

class SlamSystem {
 public:
  /// Hands each module only its sections (ImagingFrontendConfig, BackendConfig,
  /// PlaceRecognizerConfig); keeps the whole file for config() (what a session records).
  explicit SlamSystem(const Config& config);
  ~SlamSystem();

  SlamSystem(const SlamSystem&) = delete;
  SlamSystem& operator=(const SlamSystem&) = delete;

  /// Feeding thread. Rethrow an error the keyframe thread met (then the system is broken).
  void AddOdometry(const OdometrySample& sample);
  void AddScan(const RadarScan& scan);
  /// Flushes the frontend, processes the last keyframes and solves the graph once more.
  void Finish();
  /// Feeding thread: waits until every keyframe handed over so far is processed.
  void WaitIdle();

  /// Locks the keyframe thread's state for reading from another thread; keep it short
  /// enough not to stall keyframe processing (the feeding thread never waits on it).
  std::unique_lock<std::mutex> LockState() const { return std::unique_lock(state_mutex_); }

  const Config& config() const { return config_; }
  /// The keyframes the map keeps, in order (a revisit retires old views:
  /// slam/session/place_views.h).
  const std::vector<KeyframeRecord>& keyframes() const { return keyframes_; }
  /// The keyframes retired so far, in the order they were retired.
  const std::vector<RetiredKeyframe>& retired() const { return retired_; }
  const std::vector<LoopRecord>& loops() const { return loops_; }
  /// The frontend's counters as of the last Add* call returned (any thread).
  FrontendStats frontend_stats() const;
  const std::vector<SensorGeometry>& sensors() const { return frontend_->sensors(); }
  const OptimizeResult& last_optimization() const { return last_optimization_; }
  int num_solves() const { return num_solves_; }  ///< pose-graph solves so far
  /// Stage times so far (any thread).
  StageTimes times() const;
  const PoseGraph& graph() const { return *graph_; }
  /// The keyframes' cached AKAZE/ORB features (same rules as keyframes()).
  const PlaceRecognizer& recognizer() const { return *recognizer_; }

  /// Optimised T_world_anchor of every kept keyframe (odometry before the first solve).
  std::map<int, Pose2> KeyframePoses() const;
  /// Kept and retired keyframes in time order at their optimised poses (what the trajectory's
  /// correction interpolates).
  std::vector<TrajectoryAnchor> Anchors() const;
  /// The odometry trajectory as the frontend used it (jumps corrected), every sample
  /// handed to the keyframe thread (up to the last keyframe while running; all after Finish).
  const std::vector<OdometryEntry>& odometry() const { return odometry_; }
  /// The standstills that measured the gyro's bias (backend/gyro_stillness.h).
  const std::vector<GyroStandstill>& standstills() const { return standstills_; }
  /// The odometry trajectory corrected by the optimised keyframes: each sample's
  /// correction is interpolated in time between the two keyframes around it.
  std::vector<std::pair<TimestampNs, Pose2>> CorrectedTrajectory() const;
  /// Correction T_world_corrected * T_world_odom^-1 at a time (interpolated).
  Pose2 CorrectionAt(TimestampNs stamp_ns) const;
  /// A copy of the state the outputs are made from (slam/slam_snapshot.h), in time linear
  /// in keyframes, loops and odometry samples; the same rules as the accessors (hold
  /// LockState() while the keyframe thread may run).
  SlamSnapshot Capture() const;
  /// The products of `keyframe` (frontend/keyframe_products.h) as mapping makes them, once per
  /// keyframe: the detected tile, and the wall profile and lines where the walls read them (the
  /// same products as localisation's, slam/localization/localize_pipeline.h). Any thread.
  KeyframeProducts Products(const Keyframe& keyframe) const {
    return MakeKeyframeProducts(keyframe, products_);
  }
  /// The keyframe thread's longest wait for the state lock so far (any thread): what a
  /// reader holding LockState() costs SLAM.
  double keyframe_lock_wait_max_s() const;

 private:
  /// What the feeding thread hands to the keyframe thread, in order.
  struct Work {
    std::vector<OdometryEntry> odometry;  ///< odometry since the previous hand-over
    std::vector<Keyframe> keyframes;
  };

  void HandOver(bool force);
  void PublishFeedingState(double imaging_s);
  void Process(Work&& work);
  void AddKeyframe(Keyframe&& keyframe);
  /// The keyframe's node (the first is fixed: the gauge) and odometry edge; its estimate.
  Pose2 AddGraphNode(const Keyframe& keyframe);
  /// Records a match attempt and adds its loop edge if validated; caller holds state_mutex_.
  void AddLoop(const LoopAttempt& attempt, int keyframe_id);
  void Optimize();  ///< caller holds state_mutex_
  /// After a solve: each keyframe added since the last one that a loop ties to the map retires
  /// the oldest view of its place when the place has too many (slam/session/place_views.h); caller
  /// holds state_mutex_.
  void RetireRevisitedViews();
  void Retire(int id);
  /// A standstill's measurement of the gyro bias, to the graph; caller holds state_mutex_.
  void AddStandstill(const GyroStandstill& still);
  /// state_mutex_ for the keyframe thread, recording how long it waited.
  std::unique_lock<std::mutex> LockForKeyframeWork();

  // Locking contract (docs/architecture.md "Which mutex guards what"). Three mutexes;
  // lock order state_mutex_, then stats_mutex_; worker_'s is never held with another.
  Config config_;  // not changed after construction: any thread reads it
  // Feeding thread only: no lock.
  std::unique_ptr<ImagingFrontend> frontend_;
  std::vector<OdometryEntry> pending_odometry_;
  // Guarded by state_mutex_: written by the keyframe thread (or the feeding thread without
  // one) under it; read by other threads under LockState(). recognizer_ is used by the
  // keyframe thread alone, outside the lock (features and matching are the long part).
  std::unique_ptr<PoseGraph> graph_;             // GUARDED_BY(state_mutex_), solves included
  std::unique_ptr<PlaceRecognizer> recognizer_;  // keyframe thread only
  WallEdgeFinder wall_edges_;                    // keyframe thread only
  WallLandmarkTracker wall_landmarks_;           // keyframe thread only
  const bool wall_landmarks_on_;                 // UsesWallLandmarks: fixed at construction
  const KeyframeProductsConfig products_;        // what a keyframe's products are made of
  GyroStillness stillness_;                      // GUARDED_BY(state_mutex_): the odometry's
  std::vector<GyroStandstill> standstills_;      // GUARDED_BY(state_mutex_)   standstills
  TileStore tiles_;                              // thread-safe (detected tiles out of core)
  std::vector<KeyframeRecord> keyframes_;        // GUARDED_BY(state_mutex_)
  std::vector<RetiredKeyframe> retired_;         // GUARDED_BY(state_mutex_)
  std::vector<int> awaiting_retirement_check_;   // GUARDED_BY(state_mutex_): since last solve
  std::vector<LoopRecord> loops_;                // GUARDED_BY(state_mutex_)
  std::vector<OdometryEntry> odometry_;          // GUARDED_BY(state_mutex_)
  OptimizeResult last_optimization_;             // GUARDED_BY(state_mutex_)
  std::vector<SolveRecord> solves_;              // GUARDED_BY(state_mutex_)
  int num_solves_ = 0;                           // GUARDED_BY(state_mutex_)
  bool graph_dirty_ = false;                     // GUARDED_BY(state_mutex_)
  int keyframes_since_solve_ = 0;                // GUARDED_BY(state_mutex_)
  mutable std::mutex state_mutex_;
  // Guarded by stats_mutex_: counters for readers on any thread (copies returned).
  mutable std::mutex stats_mutex_;
  FrontendStats frontend_stats_;  // GUARDED_BY(stats_mutex_)
  double imaging_s_ = 0.0;        // GUARDED_BY(stats_mutex_)
  StageTimes keyframe_times_;     // GUARDED_BY(stats_mutex_): features, matching, optimisation
  double keyframe_lock_wait_max_s_ = 0.0;  // GUARDED_BY(stats_mutex_)
  // The keyframe thread (or inline without one): the hand-over FIFO of Work, in order,
  // bounded by keyframes queued; its own mutex is never held with another. Last member:
  // started after, and joined before, everything it processes with.
  OrderedWorker<Work> worker_;
};

}  // namespace uwbsar::slam
