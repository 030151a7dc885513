// The job behind `uwbsar detectors BAG`: the paper's detector experiment on a
// depart-and-return log. The run is split where it turns back; each pass is imaged into the
// world frame and cut into regions (default 2 m every 1 m); SIFT, SURF, BRISK, AKAZE and ORB
// match every D_i -> R_j (eval/region_study.h). Writes Table III (loops D_i -> R_i) and
// Table IV (AKAZE and ORB on non-loops |i - j| >= 2) as CSV and Markdown, the per-pair
// statistics for `uwbsar loops --from-stats` (eval/loop_stats.h), the loop matrix of the
// AKAZE+ORB rule, and match images.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "slam/app_config.h"

namespace uwbsar::eval {

struct DetectorsJobOptions {
  std::string bag;  ///< ROS 2 bag (directory, .db3 or .mcap)
  std::string out_dir = "out/detectors";
  std::string detectors;        ///< comma-separated subset; empty: all built
  std::vector<double> regions;  ///< empty, or region length and step in metres
  double split_path_m = 0.0;    ///< where the returning pass starts; 0: where it turns
  bool no_images = false;       ///< do not write match images (matches/)
  bool progress = false;        ///< draw a progress bar on stderr (slam/progress.h)
};

struct DetectorsJobResult {
  std::size_t scans = 0;      ///< scans imaged
  std::size_t departing = 0;  ///< ... of the departing pass
  std::size_t returning = 0;  ///< ... of the returning pass
  std::size_t regions = 0;    ///< regions of the departing pass that the passes share
  double region_length_m = 0.0;
  double region_step_m = 0.0;
  std::string table3_md, table4_md, loops_md;  ///< as written to table3.md, table4.md, loops.md
  std::string dir;                             ///< out_dir with a trailing '/'
};

/// Creates out_dir (and out_dir/matches unless no_images) before the work, images the bag
/// with config, splits and studies the passes, and writes table3.{csv,md}, table4.{csv,md},
/// stats.csv, loops.{csv,md} and matches/<detector>_D<i>_R<i>.png. Throws InputError for bad
/// options (--regions not > 0, an unknown detector), a bag with fewer than 10 imaged scans,
/// one that cannot be split into two passes, or passes that share no region.
DetectorsJobResult RunDetectorsJob(const Config& config, const DetectorsJobOptions& opts);

}  // namespace uwbsar::eval
