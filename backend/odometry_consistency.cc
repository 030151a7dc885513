#include "backend/odometry_consistency.h"

#include <algorithm>

namespace uwbsar {

int LoopToBlame(const std::vector<SolvedEdge>& edges, double max_odometry_chi2,
                double* worst_chi2) {
  int worst = -1;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (edges[i].edge->kind != EdgeKind::kOdometry) continue;
    if (worst < 0 || edges[i].chi2 > edges[static_cast<std::size_t>(worst)].chi2) {
      worst = static_cast<int>(i);
    }
  }
  if (worst_chi2 != nullptr) *worst_chi2 = worst < 0 ? 0.0 : edges[worst].chi2;
  if (worst < 0 || !(edges[static_cast<std::size_t>(worst)].chi2 > max_odometry_chi2)) return -1;
  const PoseGraphEdge& o = *edges[static_cast<std::size_t>(worst)].edge;
  const int lo = std::min(o.from_id, o.to_id), hi = std::max(o.from_id, o.to_id);
  int blamed = -1;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const SolvedEdge& e = edges[i];
    if (e.edge->kind != EdgeKind::kLoop || !e.accepted) continue;
    if (std::min(e.edge->from_id, e.edge->to_id) > lo ||
        std::max(e.edge->from_id, e.edge->to_id) < hi) {
      continue;  // does not span the edge
    }
    if (blamed < 0 || e.support <= edges[static_cast<std::size_t>(blamed)].support) {
      blamed = static_cast<int>(i);
    }
  }
  return blamed;
}

}  // namespace uwbsar
