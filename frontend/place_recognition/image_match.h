// Matching two SAR images as place recognition matches two keyframe tiles (`uwbsar match`,
// `uwbsar loops --images`): the same feature image (enhanced, masked to the measured area,
// averaged down to detectors.feature_resolution_m), the same detectors, kNN + ratio test +
// RANSAC, the paper's rule on the configured detector pair (AKAZE+ORB) with the pixel thresholds
// kept at their metric size, and the same exact metric transform (loop_validator.h). Images from
// other tools enter as 8/16-bit enhanced images; float images as uwbsar writes them are enhanced
// here.
#pragma once

#include <map>
#include <vector>

#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/features.h"
#include "frontend/place_recognition/loop_validator.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "imaging/image_grid.h"
#include "imaging/sar_image_file.h"

namespace uwbsar {

/// Features of one whole image. `grid` is the feature image's geometry in the image's own
/// frame: x along columns from the centre of pixel (0, 0), y upwards (towards row 0).
struct ImageFeatures {
  ImageGrid grid;
  FeatureImage image;  ///< at the feature resolution
  std::map<DetectorKind, FeatureSet> features;
  double source_resolution_m = 0.0;
  Point2 centre;  ///< the image's centre in its own frame (metres)
};

/// The resolution two images are matched at: detectors.feature_resolution_m, or the
/// coarser image's own pixel size when that is coarser (both images must share it).
double ImageFeatureResolution(double resolution_a_m, double resolution_b_m,
                              const PlaceRecognizerConfig& config);

/// The feature image of an image file: enhanced input is used as it is (masked to its
/// non-zero area, closed over small gaps, eroded by detectors.mask_erode_px); float input
/// goes through MakeFeatureImage like a keyframe tile; then averaged down to
/// `feature_resolution_m` (ImageFeatureResolution).
ImageFeatures ExtractImageFeatures(const SarImageFile& file,
                                   const std::vector<DetectorKind>& detectors,
                                   const PlaceRecognizerConfig& config,
                                   double feature_resolution_m);

/// A transform in the `uwbsar match` convention: a scatterer at p in A is found at
/// R(yaw) (p - c_A) + c_A + (x_m, y_m) in B, with c_A the centre of A.
struct CentredTransform {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_deg = 0.0;
};
/// From the pose of A's frame in B's frame (p_B = T_BA p_A).
CentredTransform AboutCentre(const Pose2& T_BA, const Point2& centre_a);

struct ImageMatch {
  std::map<DetectorKind, MatchResult> matches;  ///< pixels of A (query) mapped into B (train)
  std::map<DetectorKind, CentredTransform> detector_transforms;  ///< per detector with a fit
  LoopValidation validation;              ///< the pair's rule; constraint.T_ij = T_BA when accepted
  CentredTransform transform;             ///< the fused transform, valid when accepted
  CentredTransform refinement_transform;  ///< the correlation peak, valid when
                                          ///< validation.refinement.found
  bool accepted() const { return validation.accepted; }
};

/// Matches A against B with every detector both have, then applies the rule to the pair of
/// validation.detectors (reason "AKAZE and ORB were not both run" when either is missing). Both
/// feature sets must come from ExtractImageFeatures with the same config.
ImageMatch MatchImages(const ImageFeatures& a, const ImageFeatures& b,
                       const PlaceRecognizerConfig& config);

}  // namespace uwbsar
