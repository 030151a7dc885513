// Registration of a keyframe's tile against a map tile at a predicted relative pose: the evidence a
// LiDAR localiser takes from its occupancy grid, here from the map's SAR tiles. Where the feature
// rule (loop_validator.h) needs dozens of keypoints to agree with no prior, registration compares
// every pixel both tiles observed, around where the robot is predicted to be, so it still holds
// when a few objects moved: the images are high-passed and correlated only over the pixels both
// observed (dense_refinement.h), and each is normalised so that its brightest pixels saturate
// (a reflector new since the map weighs no more than the scene's bright ones). A registration is
// a constraint only when its correlation peak is high and distinct (a lone wall gives a ridge
// along itself, not a peak, and is refused).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>

#include "core/pose2.h"
#include "frontend/place_recognition/dense_refinement.h"
#include "frontend/place_recognition/map_registration_config.h"
#include "imaging/image_grid.h"

namespace uwbsar {

/// A tile as registration compares it: at the configured resolution, 8-bit, with its mask of
/// observed pixels.
struct RegistrationImage {
  FeatureImage image;
  ImageGrid grid;  ///< in the tile's anchor frame, resolution exactly config.resolution_m
  bool empty() const { return image.gray.empty(); }
};

/// From a detected tile (CV_32FC1, the map's or a keyframe's: keyframe_products.h) on `grid`:
/// averaged down to config.resolution_m (pixels not finite or <= 0 are not observed), its
/// observed pixels stretched from their minimum to config.white_percentile. Empty when the tile
/// observes nothing.
RegistrationImage MakeRegistrationImage(const cv::Mat& detected, const ImageGrid& grid,
                                        const MapRegistrationConfig& config);

/// The pixel transform (dense_refinement.h's convention: p_a = R p_b + t) of a metric T_ab (b's
/// anchor in a's): the inverse of PixelToMetricTransform (loop_validator.h).
PixelRigid MetricToPixelTransform(const ImageGrid& grid_a, const ImageGrid& grid_b,
                                  const Pose2& T_ab);

struct MapRegistration {
  bool accepted = false;
  std::string reason;  ///< why not (empty when accepted)
  Pose2 T_ab;          ///< b's anchor in a's, at the correlation peak (when found)
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  ///< (x, y, yaw) in a's frame
  DenseRefinement correlation;
};

/// Registers `b` against `a` around T_ab_predicted.
MapRegistration RegisterTiles(const RegistrationImage& a, const RegistrationImage& b,
                              const Pose2& T_ab_predicted, const MapRegistrationConfig& config);

}  // namespace uwbsar
