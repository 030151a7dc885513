// Rigid 2-D alignment of two maps by PCL ICP between their occupied cells.
#pragma once

#include <string>
#include <vector>

#include "core/pose2.h"
#include "eval/compare/compare_config.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar {

/// Outcome of AlignPointSets. `T_target_source` maps source points into the target frame.
struct AlignmentResult {
  Pose2 T_target_source;  ///< the accepted transform (the initial one if ICP was rejected)
  Pose2 T_initial;        ///< where ICP started
  bool accepted = false;  ///< ICP converged and enough source points have a partner
  std::string reason;     ///< why it was (not) accepted, in words
  int stages = 0;         ///< coarse-to-fine stages run
  int iterations = 0;     ///< ICP iterations over all stages
  long long source_points = 0;
  long long target_points = 0;
  /// Measured at the ICP result over the last stage's correspondence distance:
  double inlier_fraction = 0.0;  ///< source points with a target point within that distance
  double fitness_m2 = 0.0;       ///< PCL's fitness score: mean squared distance of those pairs
  double inlier_rmse_m = 0.0;    ///< sqrt(fitness_m2)
};

/// The centres of a grid's occupied cells, in the grid's world frame.
std::vector<Point2> OccupiedCellCenters(const OccupancyGrid& grid);

/// Coarse-to-fine ICP (one stage per `config.icp_max_correspondence_m`, each started from
/// the previous result) of `source` onto `target`, in x, y and yaw only. Point-to-point uses
/// PCL's 2-D SVD estimator; point-to-plane fits 2-D normals to the target points and solves
/// with PCL's Levenberg-Marquardt point-to-plane estimator restricted to (x, y, yaw).
/// Never throws on bad geometry: too few points or correspondences give accepted = false.
AlignmentResult AlignPointSets(const std::vector<Point2>& source, const std::vector<Point2>& target,
                               const Pose2& T_initial, const CompareConfig& config);

}  // namespace uwbsar
