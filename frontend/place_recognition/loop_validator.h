// From two detectors' matches between keyframe tiles i (a) and j (b) to a metric
// loop constraint: the paper's rule on the configured pair (loop_rule.h; AKAZE+ORB), a geometry
// check (collinear inliers cannot fix a pose), the fused transform converted exactly from pixels to
// the tiles' anchor frames, and an information matrix derived from the match: the Fisher
// information of a rigid fit to all inliers with the measured residual spread, plus configured
// floors on the standard deviations. A pair whose detectors nearly agree is refined by dense
// correlation of the two feature images when the caller has them (dense_refinement.h).
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/pose2.h"
#include "frontend/place_recognition/dense_refinement.h"
#include "frontend/place_recognition/detector_kind.h"
#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/loop_rule.h"
#include "frontend/place_recognition/place_recognition_config.h"
#include "imaging/image_grid.h"

namespace uwbsar {

/// A loop edge for the pose graph: the pose of keyframe j's anchor in keyframe i's
/// anchor frame, with information over (x, y, yaw) of that measurement in frame i
/// (the backend's residual: [R_i^T (t_j - t_i) - t_ij; yaw_j - yaw_i - yaw_ij]).
struct LoopConstraint {
  int i = 0;
  int j = 0;
  Pose2 T_ij;
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  DetectorMap<int> good_matches;  ///< of the validation pair's two detectors
  double residual_rms_m = 0.0;    ///< of all inliers under T_ij
};

struct LoopValidation {
  bool accepted = false;
  std::string reason;             ///< why rejected (empty when accepted)
  LoopDecision decision;          ///< the paper's rule and fused pixel transform
  double inlier_spread_px = 0.0;  ///< smaller principal std of the inliers in tile j
  LoopConstraint constraint;      ///< valid when accepted
  bool refinement_tried = false;  ///< the detectors nearly agreed and the images were there
  bool refined = false;           ///< accepted through the refinement (its peak is the transform)
  DenseRefinement refinement;     ///< valid when refinement_tried
};

/// The feature images of a pair (i and j as in ValidateLoop, at the resolution of the grids),
/// for the dense refinement of a near agreement; without them the paper's rule alone decides.
struct LoopImages {
  const FeatureImage* i = nullptr;
  const FeatureImage* j = nullptr;
};

/// Metric T_anchorA_anchorB of a pixel similarity p_a = s R(rot) p_b + t (scale ignored),
/// using the two tiles' grids: the exact counterpart of a pixel transform.
Pose2 PixelToMetricTransform(const ImageGrid& grid_a, const ImageGrid& grid_b, double tx_px,
                             double ty_px, double rotation_deg);

/// The smaller of the pair's good-match counts (0 when none were kept).
int MinGoodMatches(const LoopConstraint& loop);

/// Whether ValidateLoop would refine the pair given its images: the refinement is enabled and
/// the rule rejects the pair only because its detectors disagree by at most
/// refinement.near_agreement_factor times the limits (so callers unpack images only then).
bool MayRefine(const DetectorMap<MatchResult>& matches, const LoopValidationConfig& config);

/// Validates the matches of config.detectors (a detector missing from `matches` counts as
/// not matched).
LoopValidation ValidateLoop(int id_i, const ImageGrid& grid_i, int id_j, const ImageGrid& grid_j,
                            const DetectorMap<MatchResult>& matches,
                            const LoopValidationConfig& config, const LoopImages& images = {});
/// The same with the matches of config.detectors[0] and [1], in that order.
LoopValidation ValidateLoop(int id_i, const ImageGrid& grid_i, int id_j, const ImageGrid& grid_j,
                            const MatchResult& first, const MatchResult& second,
                            const LoopValidationConfig& config, const LoopImages& images = {});

}  // namespace uwbsar
