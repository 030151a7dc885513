// `uwbsar loops --images DIR`: every D<i> x R<j> image pair of a folder through the same
// matching as `uwbsar match` (the paper's loop-closure experiment on regions D1..Dn,
// R1..Rm from any SAR imager), as a loop matrix, per-pair tables and a matrix picture.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "eval/loop_stats.h"
#include "frontend/place_recognition/image_match.h"

namespace uwbsar {

struct ImagePairResult {
  int d = 0;
  int r = 0;
  ImageMatch match;  ///< D_d is A, R_r is B
};

struct ImageLoopStudy {
  std::map<int, std::string> d_files;  ///< index -> path
  std::map<int, std::string> r_files;
  std::vector<ImagePairResult> pairs;  ///< d-major
  LoopMatrix matrix;                   ///< accepted = the full validation (rule + geometry)
  std::vector<DetectorKind> rule_detectors = PaperDetectorPair();  ///< validation.detectors:
                                                                   ///< the columns of the tables
};

/// The D<i> / R<j> images of `dir` (.png, .pgm, .tif, .tiff; any case; one file per name),
/// matched every D against every R. Throws InputError when the folder has no D or no R image
/// or holds two files for one region.
ImageLoopStudy RunImageLoopStudy(const std::string& dir, double resolution_m,
                                 const std::vector<DetectorKind>& detectors,
                                 const PlaceRecognizerConfig& config, double max_image_pixels);

/// {"loops", "d", "r", "pairs": [{"d", "r", ...ImageMatchJson}]}.
nlohmann::json ImageLoopStudyJson(const ImageLoopStudy& study);
/// pairs.csv: one row per pair (good matches, scale, transform per detector, decision, reason).
std::string PairsCsv(const ImageLoopStudy& study);
/// pairs.md: the same as a Markdown table.
std::string PairsMarkdown(const ImageLoopStudy& study);
/// The loop matrix as a picture: rows D, columns R; cell shade = the weaker detector's good
/// matches, accepted pairs green with a tick.
cv::Mat DrawLoopMatrix(const ImageLoopStudy& study);

}  // namespace uwbsar
