// Synthetic false loop closures for robustness tests and benchmarks: what a
// place recognizer's false positives look like - two distant keyframes claimed
// to be close to each other (the "random outliers" of the switchable-constraints
// evaluations).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "backend/g2o_io.h"

namespace uwbsar {

struct FalseLoopOptions {
  int count = 0;
  std::uint32_t seed = 1;
  int min_id_gap = 50;             ///< |i - j| of a false loop is at least this
  double max_translation_m = 2.0;  ///< claimed offset uniform in the square +-this
  /// Information of each false loop: as confident as a real loop of the dataset.
  Eigen::Matrix3d information = Eigen::Vector3d(44.72135955, 44.72135955, 44.72135955).asDiagonal();
};

/// Appends options.count false loops between random vertex pairs of `graph` (measurement:
/// uniform offset, uniform yaw). Returns their indices in graph->edges. Deterministic in seed.
std::vector<std::size_t> AddRandomFalseLoops(G2oGraph* graph, const FalseLoopOptions& options);

}  // namespace uwbsar
