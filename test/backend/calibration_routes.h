// Test helper: an L-shaped floor route (no symmetry that would hide a heading error) driven
// with odometry whose intrinsics are known (backend/odometry_calibration.h), for the
// calibration and trial-solve tests.
#pragma once

#include <cmath>
#include <vector>

#include "backend/odometry_calibration.h"
#include "backend/pose_graph.h"
#include "backend/trajectory_metrics.h"

namespace uwbsar::testing {

/// The measured step whose correction with `calibration` is `truth` (the exact inverse of
/// CorrectOdometryStep): what a base with these intrinsics reports.
inline Pose2 MeasuredStep(const OdometryCalibration& calibration, const Pose2& truth) {
  const double d_measured = std::hypot(truth.x_m, truth.y_m) / (1.0 + calibration[kCalibScale]);
  const double yaw_measured = (truth.yaw_rad + calibration[kCalibHeadingDrift] * d_measured) /
                              (1.0 + calibration[kCalibRotation]);
  const double half_turn = 0.5 * (truth.yaw_rad - yaw_measured);
  const double c = std::cos(half_turn), s = std::sin(half_turn);
  const double k = 1.0 / (1.0 + calibration[kCalibScale]);
  return {k * (c * truth.x_m + s * truth.y_m), k * (-s * truth.x_m + c * truth.y_m), yaw_measured};
}

/// One lap of an L-shaped 12 x 8 m floor (sides of 12, 8, 6, 4, 6, 4 m) in 0.5 m steps, each
/// corner turned on the spot, from the origin heading +x back to it heading +x. `reverse`
/// drives it the other way round from there (turning to face the last side first), ending on
/// the first side heading -x.
inline std::vector<Pose2> LShapeLap(bool reverse) {
  const int sides[6] = {24, 16, 12, 8, 12, 8};
  const double turns[6] = {1, 1, 1, -1, 1, 1};  // quarter turns after each side
  std::vector<Pose2> steps;
  if (reverse) steps.push_back({0.0, 0.0, M_PI / 2});
  for (int s = 0; s < 6; ++s) {
    const int k = reverse ? 5 - s : s;
    for (int i = 0; i < sides[k]; ++i) steps.push_back({0.5, 0.0, 0.0});
    if (!reverse) steps.push_back({0.0, 0.0, turns[k] * M_PI / 2});
    if (reverse && k > 0) steps.push_back({0.0, 0.0, -turns[k - 1] * M_PI / 2});
  }
  return steps;
}

struct OdometryRun {
  std::vector<Pose2> truth;     ///< node poses
  std::vector<Pose2> measured;  ///< odometry step k: node k -> k + 1
};

inline OdometryRun DriveSteps(const OdometryCalibration& calibration,
                              const std::vector<Pose2>& steps) {
  OdometryRun run;
  Pose2 p;
  run.truth.push_back(p);
  for (const Pose2& step : steps) {
    run.measured.push_back(MeasuredStep(calibration, step));
    p = p * step;
    run.truth.push_back(p);
  }
  return run;
}

/// Nodes at the odometry's dead-reckoned poses, chained by odometry edges.
inline void BuildOdometryChain(const OdometryRun& run, PoseGraph* g) {
  Pose2 odom;
  g->AddNode(0, odom);
  for (std::size_t k = 0; k < run.measured.size(); ++k) {
    odom = odom * run.measured[k];
    g->AddNode(static_cast<int>(k + 1), odom);
    g->AddOdometryEdge(static_cast<int>(k), static_cast<int>(k + 1), run.measured[k]);
  }
}

/// ATE of the graph's estimate (nodes in id order) against `truth`.
inline double GraphAte(const PoseGraph& g, const std::vector<Pose2>& truth) {
  std::vector<Pose2> est;
  for (const auto& [id, p] : g.GetPoses()) est.push_back(p);
  return ComputeAte(est, truth).rmse_m;
}

}  // namespace uwbsar::testing
