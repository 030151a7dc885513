// Trajectory accuracy against a reference: absolute trajectory error (ATE)
// after the rigid SE(2) alignment that best fits the positions (Umeyama
// without scale), and the reference trajectories of the benchmark datasets.
#pragma once

#include <string>
#include <vector>

#include "core/pose2.h"

namespace uwbsar {

struct AteResult {
  int num_poses = 0;
  double rmse_m = 0.0;  ///< RMS position error after alignment
  double mean_m = 0.0;
  double max_m = 0.0;
  double yaw_rmse_rad = 0.0;   ///< RMS heading error after alignment
  Pose2 T_reference_estimate;  ///< the alignment applied to the estimate
};

/// ATE of `estimate` against `reference` (same length, pose k <-> pose k, at least 2).
/// Without `align`, the error in the frame both are given in (a localisation in a map whose
/// frame is the reference's): T_reference_estimate stays the identity.
/// Throws std::invalid_argument on mismatched or too short inputs.
AteResult ComputeAte(const std::vector<Pose2>& estimate, const std::vector<Pose2>& reference,
                     bool align = true);

/// Poses of a chain of relative motions: pose 0 = identity, pose k+1 = pose k * step k.
std::vector<Pose2> ComposeChain(const std::vector<Pose2>& steps);

/// The ground-truth trajectory of a dataset given as edges (`EDGE2` or `EDGE_SE2 i j dx dy
/// dtheta ...`, e.g. manhattanOlson3500_groundtruth.txt): the edges i -> i+1 composed from
/// vertex 0. Throws InputError (file and line) on a bad line or a missing link.
std::vector<Pose2> ReadGroundTruthChain(const std::string& path);

}  // namespace uwbsar
