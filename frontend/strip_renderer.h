// One SAR image of many scans in the world frame (the paper's strip images, and
// the exact global map when the poses are corrected ones): the grid covers the
// sensors' reach along all poses, and every scan is back-projected at its pose.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/keyframe.h"
#include "imaging/image_grid.h"
#include "imaging/imaging_config.h"
#include "imaging/pulse_config.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

struct StripImage {
  ImageGrid grid;  ///< in the world frame
  cv::Mat image;   ///< CV_32FC1 or CV_32FC2
  long long pixel_updates = 0;
};

/// Grid in the world frame covering every sensor's sector at every robot pose, plus margin.
ImageGrid WorldGridCovering(const std::vector<Pose2>& T_world_robot,
                            const std::vector<SensorGeometry>& sensors, double margin_m,
                            double resolution_m);

/// Back-projects `scans` into `grid`. `pose_of` may replace a scan's odometry pose
/// (e.g. with an optimised one); by default the scan's own T_world_robot is used.
StripImage RenderScans(const std::vector<ImagedScan>& scans,
                       const std::vector<SensorGeometry>& sensors, const ImageGrid& grid,
                       bool coherent, int threads,
                       const std::function<Pose2(const ImagedScan&)>& pose_of = nullptr);
/// The same by imaging.method and imaging.mode (ffbp forms sub-apertures per radar over the
/// scans in order; in paper mode the profiles must carry their quadrature, as ImagingFrontend
/// makes them for imaging.method ffbp).
StripImage RenderScans(const std::vector<ImagedScan>& scans,
                       const std::vector<SensorGeometry>& sensors, const ImageGrid& grid,
                       const ImagingConfig& imaging, const PulseConfig& pulse,
                       const std::function<Pose2(const ImagedScan&)>& pose_of = nullptr);

}  // namespace uwbsar
