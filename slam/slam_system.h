// SlamSystem: the whole pipeline behind one object, the same for offline logs
// and live drivers (DESIGN.md "Data flow"): scans and odometry go in; the
// imaging frontend closes keyframe tiles; each new keyframe gets its AKAZE and
// ORB features once, is matched against candidate keyframes near its pose
// estimate, validated loops go into the Ceres pose graph, which is re-solved
// incrementally after every accepted loop. Outputs are read from the accessors.
//
// Threading: the Add*/Finish methods are called from one thread (the feeding
// thread); in offline use everything runs on it, so the same input always gives
// the same result.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "backend/pose_graph.h"
#include "frontend/imaging_frontend.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "slam/config.h"

namespace uwbsar {

/// A keyframe as SLAM keeps it (its features live in the PlaceRecognizer).
struct KeyframeRecord {
  Keyframe keyframe;        ///< tile image dropped after use unless slam.keep_tile_images
  cv::Mat detected;         ///< detected tile (positive / magnitude, blurred) at map resolution
  ImageGrid detected_grid;  ///< its geometry in the anchor frame
};

/// Every candidate pair that was matched, with the outcome.
struct LoopRecord {
  int query_id = 0;  ///< the new keyframe (j)
  int match_id = 0;  ///< the earlier keyframe (i)
  MatchResult akaze;
  MatchResult orb;
  LoopValidation validation;
  int edge_index = -1;  ///< pose-graph edge, when the validator accepted it
  bool rejected_by_backend = false;
  double chi2 = 0.0;  ///< of the edge at the final solution
  bool accepted() const { return validation.accepted && !rejected_by_backend; }
};

/// Seconds spent per stage (wall clock, feeding thread).
struct StageTimes {
  double imaging_s = 0.0;       ///< gating, range compression, back-projection
  double features_s = 0.0;      ///< feature images and AKAZE + ORB detection
  double matching_s = 0.0;      ///< candidate search, matching and validation
  double optimization_s = 0.0;  ///< pose-graph solves
};

class SlamSystem {
 public:
  explicit SlamSystem(const Config& config);
  ~SlamSystem();

  void AddOdometry(const OdometrySample& sample);
  void AddScan(const RadarScan& scan);
  /// Flushes the frontend, processes the last keyframe and solves the graph once more.
  void Finish();

  const Config& config() const { return config_; }
  const std::vector<KeyframeRecord>& keyframes() const { return keyframes_; }
  const std::vector<LoopRecord>& loops() const { return loops_; }
  const FrontendStats& frontend_stats() const { return frontend_->stats(); }
  const std::vector<SensorGeometry>& sensors() const { return frontend_->sensors(); }
  const OptimizeResult& last_optimization() const { return last_optimization_; }
  const StageTimes& times() const { return times_; }
  const PoseGraph& graph() const { return *graph_; }

  /// Optimised T_world_anchor of every keyframe (odometry before the first solve).
  std::map<int, Pose2> KeyframePoses() const;
  /// The odometry trajectory as the frontend used it (jumps corrected), every sample.
  const std::vector<OdometryEntry>& odometry() const { return odometry_; }
  /// The odometry trajectory corrected by the optimised keyframes: each sample's
  /// correction is interpolated in time between the two keyframes around it.
  std::vector<std::pair<TimestampNs, Pose2>> CorrectedTrajectory() const;
  /// Correction T_world_corrected * T_world_odom^-1 at a time (interpolated).
  Pose2 CorrectionAt(TimestampNs stamp_ns) const;

 private:
  void ProcessKeyframes();
  void AddKeyframe(Keyframe&& keyframe);
  void Optimize();

  Config config_;
  std::unique_ptr<ImagingFrontend> frontend_;
  std::unique_ptr<PoseGraph> graph_;
  std::unique_ptr<PlaceRecognizer> recognizer_;
  std::vector<KeyframeRecord> keyframes_;
  std::vector<LoopRecord> loops_;
  std::vector<OdometryEntry> odometry_;
  OptimizeResult last_optimization_;
  StageTimes times_;
  bool graph_dirty_ = false;
  int keyframes_since_solve_ = 0;
};

}  // namespace uwbsar
