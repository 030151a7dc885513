// The jobs behind `uwbsar match A B` and `uwbsar loops`: two SAR images matched as place
// recognition matches two keyframe tiles (frontend/place_recognition/image_match.h), and the
// D x R loop matrix of the AKAZE+ORB rule, re-evaluated on recorded per-pair statistics
// (eval/loop_stats.h) or measured on a folder of region images (eval/image_loop_study.h).
// The command line prints what they return.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "eval/loop_stats.h"
#include "frontend/place_recognition/image_match.h"
#include "slam/app_config.h"

namespace uwbsar::eval {

struct ImageMatchJobOptions {
  std::string a, b;             ///< the images: PNG/PGM, float TIFF, or a grid YAML
  double resolution_m = 0.005;  ///< metres per pixel when no grid YAML describes one
  std::string detectors;        ///< comma-separated (ParseDetectorList); "": the loop rule's pair
                                ///< (place_recognition.validation.detectors)
  std::string out_dir;          ///< also write match.png and match.json here; empty: not written
};

struct ImageMatchJobResult {
  ImageMatch match;
  nlohmann::json json;             ///< ImageMatchJson(match), as match.json holds it
  std::vector<std::string> files;  ///< what was written (out_dir), in order
};

/// Parses the detectors, creates out_dir (before the work), reads both images (refused
/// beyond limits.max_map_image_pixels, or when their metric sizes differ by more than 4x),
/// extracts features at a common resolution and matches them with config's rule. A rejection
/// is an outcome (match.accepted() false); bad input throws InputError.
ImageMatchJobResult RunImageMatchJob(const Config& config, const ImageMatchJobOptions& options);

struct LoopMatrixJobResult {
  LoopMatrix matrix;
  /// {"loops", "d", "r"}; from images also "pairs" (ImageLoopStudyJson).
  nlohmann::json json;
  std::vector<std::string> files;  ///< what was written (out_dir), in order
};

/// `loops --from-stats`: the loop matrix of config.place_recognition.validation on the
/// per-pair statistics of `stats_csv` (the stats.csv of `uwbsar detectors`).
LoopMatrixJobResult LoopMatrixFromStats(const Config& config, const std::string& stats_csv);

/// `loops --images`: every D<i> x R<j> pair of `images_dir` matched as RunImageMatchJob
/// does; with `out_dir` (created before the work) also pairs.csv, pairs.md, loops.json and
/// matrix.png there.
LoopMatrixJobResult LoopMatrixFromImages(const Config& config, const std::string& images_dir,
                                         double resolution_m, const std::string& detectors,
                                         const std::string& out_dir);

}  // namespace uwbsar::eval
