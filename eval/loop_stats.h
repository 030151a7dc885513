// Recorded per-pair match statistics (one CSV row per region or keyframe pair) and
// the loop matrix the paper's rule gives on them, so thresholds can be tuned on
// logged figures without images (`uwbsar loops --from-stats`). Columns, any order,
// extra columns ignored, for the validation pair (the paper's: akaze, orb):
//   d,r,n_akaze,scale_akaze,tx_akaze_px,ty_akaze_px,rot_akaze_deg,
//     n_orb,scale_orb,tx_orb_px,ty_orb_px,rot_orb_deg
// A transform field that is empty or "-" means the detector found no transform.
#pragma once

#include <string>
#include <vector>

#include "core/limits_config.h"
#include "frontend/place_recognition/loop_rule.h"
#include "frontend/place_recognition/place_recognition_config.h"

namespace uwbsar {

struct PairStats {
  int d = 0;                             ///< departing region / older keyframe index
  int r = 0;                             ///< returning region / newer keyframe index
  DetectorMap<DetectorStats> detectors;  ///< the pair's two detectors
};

/// The column names, in the canonical order, for the detector pair `detectors`.
std::vector<std::string> PairStatsColumns(
    const std::vector<DetectorKind>& detectors = PaperDetectorPair());

/// Parses the CSV text (columns of `detectors`); throws InputError naming `source`, the line
/// and the column on malformed numbers, missing columns or duplicate (d, r) pairs.
std::vector<PairStats> ParsePairStats(
    const std::string& csv_text, const std::string& source,
    const std::vector<DetectorKind>& detectors = PaperDetectorPair());
/// The file must be a regular file of at most `max_mb` MiB (limits.max_input_file_mb).
std::vector<PairStats> ReadPairStatsFile(
    const std::string& path, const std::vector<DetectorKind>& detectors = PaperDetectorPair(),
    double max_mb = LimitsConfig{}.max_input_file_mb);

/// One CSV row (canonical order) for `stats`, without a newline.
std::string PairStatsRow(const PairStats& stats,
                         const std::vector<DetectorKind>& detectors = PaperDetectorPair());

struct LoopMatrix {
  std::vector<int> d_ids;                         ///< sorted distinct d values (rows)
  std::vector<int> r_ids;                         ///< sorted distinct r values (columns)
  std::vector<std::vector<int>> loops;            ///< 0/1, rows x columns; pairs not listed are 0
  std::vector<std::vector<std::string>> reasons;  ///< "" when accepted or not listed
};

/// The rule on config.detectors' figures of each pair.
LoopMatrix EvaluateLoopMatrix(const std::vector<PairStats>& stats,
                              const LoopValidationConfig& config);

}  // namespace uwbsar
