// Consistency of the map after a solve: a loop that does not belong bends the
// odometry chain between its ends, and where the chain is short the bend shows as an
// odometry edge far outside its noise even when the loop's own residual looks fine (the
// robust loss lets the loop win). After each solve the odometry edge with the largest
// chi2 is tested; above the limit, one accepted loop spanning it along the chain is blamed
// and rejected, and the graph re-solved (PoseGraph::Optimize).
#pragma once

#include <vector>

#include "backend/pose_graph.h"

namespace uwbsar {

/// The state of one edge at a solution, as the consistency test reads it.
struct SolvedEdge {
  const PoseGraphEdge* edge = nullptr;
  double chi2 = 0.0;
  bool accepted = true;  ///< loops: not rejected (odometry edges always count)
  int support = -1;      ///< loops: consistent neighbouring loops (-1: not computed)
};

/// Index into `edges` of the accepted loop to reject, or -1 when every odometry edge has
/// chi2 <= max_odometry_chi2. Blamed: among the accepted loops whose ends span the worst
/// odometry edge (node ids run along the chain), the least supported, then the latest.
/// `worst_chi2` (optional) receives the largest odometry chi2.
int LoopToBlame(const std::vector<SolvedEdge>& edges, double max_odometry_chi2,
                double* worst_chi2 = nullptr);

}  // namespace uwbsar
