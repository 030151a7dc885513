// Printing and drawing what `uwbsar match` and `uwbsar loops --images` found: the JSON
// document of one image pair, the match picture, and the detector list flag.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/place_recognition/image_match.h"

namespace uwbsar {

/// {"accepted", "reason", "transform": {x_m, y_m, yaw_deg} or null, "detectors": {"akaze":
/// {"keypoints": [a, b], "ratio_matches", "good", "scale", "x_m", "y_m", "yaw_deg"}, ...}}.
/// reason is "" for an accepted pair, else the validator's words (as loops.csv).
nlohmann::json ImageMatchJson(const ImageMatch& match);

/// Both feature images side by side (A left), each detector's good matches drawn in its
/// colour (AKAZE green, ORB yellow, others cyan) over the ratio-test matches (dark red).
cv::Mat DrawImageMatch(const ImageFeatures& a, const ImageFeatures& b, const ImageMatch& match);

/// "akaze,orb,..." (any case) -> detectors, duplicates dropped; throws InputError naming
/// an unknown or unavailable detector.
std::vector<DetectorKind> ParseDetectorList(const std::string& list);

}  // namespace uwbsar
