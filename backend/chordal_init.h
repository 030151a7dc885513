// Initial estimate of a planar pose graph by chordal relaxation (Martinec & Pajdla
// 2007; Carlone et al., "Initialization techniques for 3D SLAM", 2015): rotations
// first, as 2x2 matrices from a linear least-squares problem, projected back onto
// SO(2); then positions from a second linear problem with the rotations fixed. Both
// are convex, so the result does not depend on the (possibly poor) guess; it lies in
// the basin of the right optimum for graphs whose loops are correct, where
// Levenberg-Marquardt from dead-reckoning odometry may get stuck (e.g. MIT-B).
#pragma once

#include <map>
#include <vector>

#include "backend/pose_graph.h"

namespace uwbsar {

/// Poses for every node of `guess` (the ones not reached by any edge keep their guess).
/// `anchor_id` keeps its guessed pose (the gauge). Edges must refer to nodes of `guess`.
std::map<int, Pose2> ChordalInitialization(const std::map<int, Pose2>& guess,
                                           const std::vector<PoseGraphEdge>& edges, int anchor_id);

}  // namespace uwbsar
