// `uwbsar localize BAG --map SESSION`: a log imaged keyframe by keyframe (the imaging
// frontend only: no place recognition within the run, no map growth) and each keyframe
// localised in the saved map (slam/localization/localizer.h), imaging on the feeding thread and the
// features and localisation on a keyframe thread (slam/localization/localize_pipeline.h). Outputs:
// trajectory.tum in the map frame (from the first fix on), localize.csv (status per
// keyframe), summary.json (with the latest map -> odom correction), written by
// slam/outputs/localize_outputs.h.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backend/backend_config.h"
#include "backend/trajectory_metrics.h"
#include "core/message.h"
#include "frontend/imaging_frontend.h"
#include "frontend/odometry_buffer.h"
#include "slam/app_config.h"
#include "slam/localization/localizer.h"
#include "slam/session/session_data.h"

namespace uwbsar::slam {

struct LocalizeRun {
  std::string input;
  std::vector<LocalizedKeyframe> keyframes;
  std::vector<OdometryEntry> odometry;
  std::vector<OdometrySample> ground_truth;
  FrontendStats frontend_stats;  ///< the scans and odometry read
  BackendConfig backend;         ///< the odometry calibration applied (summary.json)
  double processing_s = 0.0;     ///< imaging, features and localisation (not the log source)
  double log_duration_s = 0.0;
  int first_fix = -1;                  ///< index into keyframes, -1 when never placed
  double first_fix_path_m = 0.0;       ///< odometry path from the start to the first fix
  double first_fix_time_s = 0.0;       ///< log time from the first odometry to the first fix
  TimestampNs first_fix_stamp_ns = 0;  ///< when the first fix was known (its tile's last scan)

  /// The odometry in the map frame, each sample corrected by the latest placed keyframe at
  /// or before it (earliest placed one before that); `tracking_only` drops the samples
  /// whose keyframe is lost. Empty when never placed.
  std::vector<std::pair<TimestampNs, Pose2>> Trajectory(bool tracking_only) const;
};

/// Localises what `source` emits: scans and odometry through FeedScanOrOdometry, ground
/// truth kept for the evaluation. `on_message` (optional) is called with each message's stamp.
LocalizeRun LocalizeSource(const SessionData& map, const Config& config,
                           const std::string& description, MessageSource& source,
                           const std::function<void(TimestampNs)>& on_message = nullptr);
/// A ROS 2 bag; `progress` draws a bar on stderr (slam/progress.h).
LocalizeRun LocalizeBag(const SessionData& map, const Config& config, const std::string& bag,
                        bool progress = false);
/// A simulated run (as MapSimulationInScene: the scene from scene_seed, odometry in its
/// own frame T_odom_world).
LocalizeRun LocalizeSimulation(const SessionData& map, const Config& config,
                               const std::string& map_yaml, const std::string& route,
                               std::uint64_t scene_seed, std::uint64_t seed,
                               const Pose2& T_odom_world = {});

}  // namespace uwbsar::slam
