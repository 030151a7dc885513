// The paper's loop-closure rule ("Identifying Loop Closures while Exploring") on
// per-detector match statistics only, so that it can be re-run on logged figures
// (`uwbsar loops --from-stats`): both detectors of the configured pair (validation.detectors,
// the paper's AKAZE and ORB) need more than N good matches, scales in [min, max], and their
// tx, ty and rotation must agree; the fused transform is the good-match-weighted mean of the two.
#pragma once

#include <string>

#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/place_recognition_config.h"

namespace uwbsar {

/// What the rule needs from one detector's match (pixel transform of b into a).
struct DetectorStats {
  int good_matches = 0;
  bool has_transform = false;
  double scale = 0.0;
  double tx_px = 0.0;
  double ty_px = 0.0;
  double rotation_deg = 0.0;
};

DetectorStats StatsOf(const MatchResult& match);

struct LoopDecision {
  bool accepted = false;
  std::string reason;  ///< why rejected: names the detector, the figure and the limit
  double tx_px = 0.0;  ///< fused (good-match-weighted) transform, valid when accepted
  double ty_px = 0.0;
  double rotation_deg = 0.0;
};

/// `first` and `second` are the figures of config.detectors[0] and [1] (whose names the
/// reasons give).
LoopDecision ApplyLoopRule(const DetectorStats& first, const DetectorStats& second,
                           const LoopValidationConfig& config);

/// Wraps degrees to [-180, 180).
double WrapDegrees(double deg);

}  // namespace uwbsar
