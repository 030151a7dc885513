// Nearest-neighbour distances between 2-D point sets (PCL KD-tree), and their summary.
#pragma once

#include <vector>

#include "core/pose2.h"

namespace uwbsar {

/// For every query point, the distance to the nearest reference point. Empty when
/// `reference` is empty (no distance is defined).
std::vector<double> NearestDistances(const std::vector<Point2>& queries,
                                     const std::vector<Point2>& reference);

/// Mean, 95th percentile (nearest rank: the ceil(0.95 n)-th smallest) and maximum.
/// All NaN when there are no distances.
struct DistanceStats {
  long long count = 0;
  double mean_m = 0.0;
  double p95_m = 0.0;
  double max_m = 0.0;
};
DistanceStats SummarizeDistances(std::vector<double> distances_m);

}  // namespace uwbsar
