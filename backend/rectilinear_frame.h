// The rectilinear ("Manhattan") frame that best fits a set of wall directions: the angle phi
// such that every wall's normal is phi plus a whole number of quarter turns, as nearly as the
// walls allow (the weighted circular mean of 4 x normal, divided by 4), and how far the walls
// stray from it (weighted rms). A square building's walls stray only by their measurement
// error; a building that is not square strays by its corners' departure from 90 deg (one 2 deg
// off square: walls about 1 deg either side of the best frame).
#pragma once

#include <cmath>
#include <vector>

#include "core/pose2.h"

namespace uwbsar {

struct RectilinearFit {
  double frame_rad = 0.0;  ///< in [-pi/4, pi/4)
  double rms_rad = 0.0;    ///< weighted rms of each normal's departure from the frame
  double weight = 0.0;     ///< the weights' sum (0: nothing fitted)
};

/// `normals_rad[i]` weighs `weights[i]` (>= 0; the two the same length).
inline RectilinearFit FitRectilinearFrame(const std::vector<double>& normals_rad,
                                          const std::vector<double>& weights) {
  RectilinearFit fit;
  double s = 0.0, c = 0.0;
  for (std::size_t i = 0; i < normals_rad.size(); ++i) {
    s += weights[i] * std::sin(4.0 * normals_rad[i]);
    c += weights[i] * std::cos(4.0 * normals_rad[i]);
    fit.weight += weights[i];
  }
  if (!(fit.weight > 0.0)) return fit;
  fit.frame_rad = 0.25 * std::atan2(s, c);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < normals_rad.size(); ++i) {
    const double d = 0.25 * NormalizeAngle(4.0 * (normals_rad[i] - fit.frame_rad));  // +-45 deg
    sum2 += weights[i] * d * d;
  }
  fit.rms_rad = std::sqrt(sum2 / fit.weight);
  return fit;
}

}  // namespace uwbsar
