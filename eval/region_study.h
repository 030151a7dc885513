// The paper's detector experiment ("Evaluating Feature Detectors on SAR Images"):
// the departing (D) and returning (R) passes are imaged separately into one world
// (odometry) frame, cut into regions of region_length_m every region_step_m along
// the departing path's main axis (paper: 400 px = 2 m, 1 m step: D1..D6, R1..R6, with
// R_i the same world rectangle as D_i), and every detector matches every D_i -> R_j.
// The results feed Table III (loops D_i -> R_i), Table IV (non-loops) and the loop
// matrix of the AKAZE+ORB rule. Features are computed once per region.
#pragma once

#include <map>
#include <vector>

#include "eval/loop_stats.h"
#include "frontend/keyframe.h"
#include "frontend/keyframe_config.h"
#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/features.h"
#include "frontend/place_recognition/loop_validator.h"
#include "frontend/place_recognition/place_recognition_config.h"
#include "imaging/enhance_config.h"
#include "imaging/image_grid.h"
#include "imaging/imaging_config.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

/// The sections the region study reads (imaging, keyframe margin, place recognition and the
/// feature image's enhancement), from any configuration holding them.
struct RegionStudyConfig {
  ImagingConfig imaging;
  KeyframeConfig keyframe;
  PlaceRecognitionConfig place_recognition;
  EnhanceConfig enhance;

  RegionStudyConfig() = default;
  template <class Config>
  RegionStudyConfig(const Config& config)  // NOLINT(google-explicit-constructor)
      : imaging(config.imaging),
        keyframe(config.keyframe),
        place_recognition(config.place_recognition),
        enhance(config.enhance) {}
};

struct RegionStudyOptions {
  double region_length_m = 2.0;  ///< paper: 400 px at 5 mm
  double region_step_m = 1.0;    ///< paper: 200 px
  std::vector<DetectorKind> detectors = AvailableDetectors();
};

struct StudyRegion {
  int index = 0;   ///< 1-based, as the paper's D1.. / R1..
  cv::Rect rect;   ///< in the strip image
  ImageGrid grid;  ///< the crop's geometry in the world (odometry) frame
  FeatureImage image;
  std::map<DetectorKind, FeatureSet> features;
};

struct RegionPair {
  int d = 0;  ///< region indices, 1-based
  int r = 0;
  std::map<DetectorKind, MatchResult> matches;  ///< R_r pixels mapped into D_d pixels
  LoopValidation validation;  ///< AKAZE+ORB rule, geometry check and metric transform
};

struct RegionStudy {
  ImageGrid strip_grid;  ///< world frame, covers both passes
  cv::Mat d_strip;       ///< SAR strips of each pass (float, as imaged)
  cv::Mat r_strip;
  std::vector<StudyRegion> d_regions;
  std::vector<StudyRegion> r_regions;
  std::vector<RegionPair> pairs;  ///< every (d, r), d-major
  std::vector<PairStats> stats;  ///< the validation pair's statistics per pair (loops --from-stats)
  std::vector<DetectorKind> stats_detectors;  ///< that pair (validation.detectors)

  const RegionPair* Find(int d, int r) const;
};

/// Index of the scan where the run turns back: the one farthest from the first scan.
/// Scans before it are the departing pass, the rest the returning pass.
std::size_t TurnaroundIndex(const std::vector<ImagedScan>& scans);

/// Runs the experiment. Regions that either pass observed on less than half of their
/// pixels are dropped. Throws std::invalid_argument when a pass is empty.
RegionStudy RunRegionStudy(const std::vector<ImagedScan>& depart,
                           const std::vector<ImagedScan>& ret,
                           const std::vector<SensorGeometry>& sensors,
                           const RegionStudyConfig& config, const RegionStudyOptions& options);

}  // namespace uwbsar
