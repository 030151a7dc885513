// Back-projection of one range profile into an image (paper eqs. R = |P - U|,
// bin = R / Delta d, SAR = sum_i S_i): every pixel of the sensor's FOV sector
// gets the profile's value at its range, linearly interpolated. Real profiles
// add into CV_32FC1 images (paper mode); analytic profiles into CV_32FC2
// (coherent mode). The analytic table is the upsampled analytic signal, whose
// phase already carries exp(j 2 pi fc (t - 2R/c)), so interpolating it at the
// pixel's delay applies the exp(j 4 pi fc R / c) focusing term exactly.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "imaging/image_grid.h"
#include "imaging/range_profile.h"
#include "imaging/sector_spans.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

class BackProjector {
 public:
  /// `parallel_stripes` <= 1 runs on the calling thread; otherwise cv::parallel_for_.
  explicit BackProjector(int parallel_stripes = 2) : stripes_(parallel_stripes) {}

  /// Adds `profile` into `image` (grid-sized; type CV_32FC1 or CV_32FC2 to match the profile)
  /// for a sensor at T_grid_sensor. Returns the number of pixels updated; if `touched`
  /// is given it receives the bounding box of those pixels (empty when none).
  long long Accumulate(const RangeProfile& profile, const Pose2& T_grid_sensor,
                       const SensorGeometry& geometry, const ImageGrid& grid, cv::Mat* image,
                       cv::Rect* touched = nullptr);

 private:
  int stripes_;
  std::vector<RowSpan> spans_;  // reused between calls
};

/// An image of zeros of the right type for the mode and grid.
cv::Mat MakeSarImage(const ImageGrid& grid, bool coherent);

}  // namespace uwbsar
