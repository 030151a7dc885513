#include "frontend/place_recognition/image_match.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "frontend/place_recognition/place_recognizer.h"

namespace uwbsar {
namespace {

/// The paper's feature image of an enhanced (8-bit) input: the pixels as they are; the
/// mask is the measured (non-zero) area with small gaps closed (dark speckle quantised to
/// 0 inside the scene), eroded like a tile's so that the edges of the measured area (range
/// limits, blind zone) are not taken for scene features.
cv::Mat MeasuredMask(const cv::Mat& observed, int erode_px) {
  cv::Mat mask = observed.clone();
  if (erode_px > 0) {
    const cv::Mat kernel =
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * erode_px + 1, 2 * erode_px + 1));
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, kernel);
    cv::erode(mask, mask, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  }
  return mask;
}

FeatureImage EnhancedFeatureImage(const SarImageFile& file, int erode_px) {
  FeatureImage out;
  out.gray = file.image;
  out.mask = MeasuredMask(file.observed, erode_px);
  return out;
}

CentredTransform DetectorTransform(const ImageFeatures& a, const ImageFeatures& b,
                                   const MatchResult& m) {
  return AboutCentre(PixelToMetricTransform(b.grid, a.grid, m.tx_px, m.ty_px, m.rotation_deg),
                     a.centre);
}

}  // namespace

CentredTransform AboutCentre(const Pose2& T_BA, const Point2& centre_a) {
  const Point2 moved = T_BA * centre_a;
  return {moved.x_m - centre_a.x_m, moved.y_m - centre_a.y_m, T_BA.yaw_rad * 180.0 / M_PI};
}

ImageFeatures ExtractImageFeatures(const SarImageFile& file,
                                   const std::vector<DetectorKind>& detectors,
                                   const PlaceRecognizerConfig& config,
                                   double feature_resolution_m) {
  const DetectorConfig& d = config.place_recognition.detectors;
  ImageFeatures out;
  out.source_resolution_m = file.grid.resolution_m;
  // The image's own frame: pixel (0, 0) at the origin, x along columns, y upwards.
  ImageGrid grid;
  grid.resolution_m = file.grid.resolution_m;
  grid.rows = file.image.rows;
  grid.cols = file.image.cols;
  out.centre = grid.PixelToMetric(0.5 * (grid.cols - 1), 0.5 * (grid.rows - 1));
  FeatureImage image = file.enhanced
                           ? EnhancedFeatureImage(file, d.mask_erode_px)
                           : MakeFeatureImage(file.image, config.enhance, d.mask_erode_px);
  // NaN/inf pixels scattered inside the scene (dropouts) are not edges of the measured area:
  // their gaps are closed as an enhanced image's dark speckle (a float TIFF with 1/9 NaN
  // pixels had no feature left after the erosion).
  if (!file.enhanced && file.nonfinite_values > 0) {
    image.mask = MeasuredMask(file.observed, d.mask_erode_px);
  }
  out.image = DownsampleFeatureImage(
      std::move(image), feature_resolution_m / file.grid.resolution_m, d.white_percentile, &grid);
  out.grid = grid;
  for (DetectorKind kind : detectors) out.features[kind] = ComputeFeatures(out.image, kind, d);
  return out;
}

double ImageFeatureResolution(double resolution_a_m, double resolution_b_m,
                              const PlaceRecognizerConfig& config) {
  return std::max(
      {config.place_recognition.detectors.feature_resolution_m, resolution_a_m, resolution_b_m});
}

ImageMatch MatchImages(const ImageFeatures& a, const ImageFeatures& b,
                       const PlaceRecognizerConfig& config) {
  // Pixel thresholds at the feature resolution, as the place recognizer uses them.
  const PlaceRecognitionConfig pr =
      AtFeatureResolution(config.place_recognition, a.grid.resolution_m / config.tile_pixel_m);
  ImageMatch out;
  for (const auto& [kind, features_a] : a.features) {
    const auto it = b.features.find(kind);
    if (it == b.features.end()) continue;
    // B is the "train" side: the fitted transform maps A's pixels into B's.
    MatchResult m = MatchFeatures(it->second, features_a, pr.matching);
    if (m.has_transform) out.detector_transforms[kind] = DetectorTransform(a, b, m);
    out.matches[kind] = std::move(m);
  }
  const std::vector<DetectorKind>& pair = pr.validation.detectors;
  if (!out.matches.count(pair[0]) || !out.matches.count(pair[1])) {
    out.validation.reason =
        std::string(DetectorName(pair[0])) + " and " + DetectorName(pair[1]) + " were not both run";
    return out;
  }
  // i = B, j = A: the constraint is the pose of A's frame in B's frame.
  out.validation =
      ValidateLoop(2, b.grid, 1, a.grid, out.matches, pr.validation, {&b.image, &a.image});
  if (out.validation.accepted)
    out.transform = AboutCentre(out.validation.constraint.T_ij, a.centre);
  if (out.validation.refinement.found) {
    const PixelRigid& r = out.validation.refinement.transform;
    out.refinement_transform = AboutCentre(
        PixelToMetricTransform(b.grid, a.grid, r.tx_px, r.ty_px, r.rotation_deg), a.centre);
  }
  return out;
}

}  // namespace uwbsar
