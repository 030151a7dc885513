// Scoring of a simulated tour mapped by SlamSystem against its ground truth:
// ATE of SLAM and of odometry alone, loops (candidates, validated, accepted, false ones),
// whether the ring closed, and recall at revisits.
//
// Definitions (the truth is the simulator's ground truth; a keyframe's true anchor is the
// true robot pose at its stamp composed with its odometry robot-to-anchor offset):
//  - false loop: a validated loop whose transform is farther than 0.2 m or 5 deg from the
//    truth between its anchors;
//  - candidate with true overlap: a matched pair whose true anchors lie within
//    overlap_m of each other (half a tile by default: the tiles share most of their area);
//  - revisit: a maximal run of consecutive query keyframes that each have a candidate
//    with true overlap; it is recalled when at least one of its loops is accepted;
//  - ring closed: SLAM ATE at least 3x better than odometry alone;
//  - a wall edge's error: its measured offset minus the true one, across the path;
//  - an accepted loop's error: its measured transform against the true one (translation
//    length, |yaw|), beside the standard deviation its information claims (the square root
//    of the covariance's diagonal: the mean of x and y, and yaw): a claimed sigma far above the
//    error means the loops are weighted below what they measure.
#pragma once

#include <string>

#include "slam/map_job.h"

namespace uwbsar::eval {

struct TourEvaluation {
  double travel_m = 0.0;  ///< true path length
  double ate_m = 0.0;
  double odometry_ate_m = 0.0;
  int keyframes = 0;
  int candidates = 0;  ///< matched pairs
  int validated = 0;   ///< passed the rule of the validation pair (AKAZE+ORB)
  int accepted = 0;    ///< validated and kept by the backend
  int false_validated = 0;
  int false_accepted = 0;
  int overlap_candidates = 0;  ///< candidates with true overlap
  int overlap_accepted = 0;    ///< of those, accepted
  int revisits = 0;
  int revisits_recalled = 0;
  double longest_loop_path_m = 0.0;  ///< path between the ends of the longest accepted loop
  int wall_edges = 0;                ///< wall-profile edges (slam/wall_edges.h)
  int wall_rejected = 0;             ///< of those, rejected by the backend
  double wall_error_rms_m = 0.0;     ///< sideways error of the accepted ones against the truth
  double wall_error_max_m = 0.0;
  int landmarks = 0;                     ///< wall landmarks (slam/wall_landmarks.h)
  int landmark_observations = 0;         ///< their observations
  int landmark_rejected = 0;             ///< of those, rejected by the backend
  double landmark_error_rms_m = 0.0;     ///< accepted observations about their wall's true line
  double landmark_error_max_m = 0.0;     ///< (the line through all of them, placed by the truth)
  double loop_error_rms_m = 0.0;         ///< accepted loops, translation
  double loop_error_rms_yaw_rad = 0.0;   ///< accepted loops, rotation
  double loop_sigma_mean_m = 0.0;        ///< their claimed translation sigma, mean
  double loop_sigma_mean_yaw_rad = 0.0;  ///< their claimed rotation sigma, mean
  bool ring_closed = false;

  double candidate_recall() const {
    return overlap_candidates > 0 ? double(overlap_accepted) / overlap_candidates : 0.0;
  }
  double revisit_recall() const {
    return revisits > 0 ? double(revisits_recalled) / revisits : 0.0;
  }
};

TourEvaluation EvaluateTour(const slam::MapRun& run, double overlap_m = 1.0);

/// One line: travel, ATE (odometry, ratio), loops, false loops, recalls.
std::string FormatTourEvaluation(const TourEvaluation& e);

/// The true robot pose at `t`: the ground-truth sample nearest it (`truth` sorted by stamp).
Pose2 TruePoseAt(const std::vector<OdometrySample>& truth, TimestampNs t);

}  // namespace uwbsar::eval
