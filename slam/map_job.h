// The main job behind `uwbsar map` and `uwbsar demo`: stream a log (a ROS 2 bag
// or a simulated run) through a SlamSystem, then evaluate the result against
// ground truth when there is one. Writing the outputs is map_outputs.h.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backend/trajectory_metrics.h"
#include "core/message.h"
#include "drivers/rosbag/bag_storage.h"
#include "slam/app_config.h"
#include "slam/slam_system.h"

namespace uwbsar::slam {

struct MapRun {
  std::shared_ptr<SlamSystem> slam;  ///< shared: a live snapshot writer reads it on its own thread
  std::vector<OdometrySample> ground_truth;  ///< from the bag's topic or --ground-truth
  std::string input;                         ///< what was mapped (path or description)
  /// The recording's identity (slam/jobs/saved_session.h BagFingerprint, set by `uwbsar map`):
  /// a session refuses to join it twice. "" for sources without one (the session then uses
  /// the input and first stamp).
  std::string fingerprint;
  TimestampNs first_stamp_ns = 0;
  TimestampNs last_stamp_ns = 0;
  long long messages = 0;
  long long radar_messages = 0;
  long long odometry_messages = 0;
  double processing_s = 0.0;  ///< MapBag: wall time of bag reading + SLAM; MapSource: SLAM's
                              ///< own time (the source, e.g. the simulator, is not counted)
  /// The span of log the map was built from: first to last scan imaged into a keyframe
  /// (a stray message stamped far away does not count), else of the messages read;
  /// computed in doubles, so no stamps overflow it.
  double log_duration_s() const;
};

/// Maps a ROS 2 bag (directory, .db3 or .mcap). `progress` draws a bar on stderr
/// (slam/progress.h).
/// Throws InputError for bags that cannot be mapped (no odometry or radar topic,
/// no scan overlapping the odometry, too short for one keyframe).
MapRun MapBag(const Config& config, const std::string& bag_path, bool progress,
              const rosbag::BagReadOptions& read_options = {});

/// Maps what `source` emits, each message through Feed(), with the same checks; `on_message`
/// (optional) is called after each. processing_s counts only the time spent in the SlamSystem.
MapRun MapSource(const Config& config, const std::string& description, MessageSource& source,
                 const std::function<void(MapRun*)>& on_message = nullptr);

/// The one way a message enters a mapping run, offline and live: CountMessage, then
/// FeedSlam. Events are not SLAM's (the live recorder keeps them).
void Feed(MapRun* run, const Message& m);
/// Counts `m` in `run` (messages by kind; first and last stamp = the smallest and largest
/// seen) and keeps a ground-truth pose. The live processor calls it under its lock.
void CountMessage(MapRun* run, const Message& m);
/// Hands a radar scan or odometry sample to `slam`; other kinds are not SLAM's.
void FeedSlam(SlamSystem& slam, const Message& m);

/// Maps a simulated run (drivers/sim: `map_yaml`, built-in route name or waypoints
/// file, seed) in memory, with its ground truth: the demo, tests and benchmarks.
/// `on_message` (optional) is called after each message, e.g. to time the run; `progress`
/// draws a bar on stderr (slam/progress.h).
MapRun MapSimulation(const Config& config, const std::string& map_yaml, const std::string& route,
                     std::uint64_t seed, const std::function<void(MapRun*)>& on_message = nullptr,
                     bool progress = false);

/// Checks that the run produced a map; throws InputError with the reason if not.
void CheckMappable(const MapRun& run);

/// The ground truth of a run given as a file (`--ground-truth` of `uwbsar map` and
/// `calibrate`), which takes the place of the bag's slam.ground_truth_topic: a TUM trajectory
/// (drivers/logs/tum_reader.h), planar poses with their stamps in file order. Throws
/// InputError naming the file and line on a malformed line or an empty file, and naming the
/// file when it is not a regular file of at most `max_mb` MiB (limits.max_input_file_mb).
/// `lines` (optional) receives each pose's line number, to name it in later messages.
std::vector<OdometrySample> ReadGroundTruthFile(const std::string& tum_path, double max_mb,
                                                std::vector<int>* lines = nullptr);

/// Trajectory error of `estimate` against `reference`: poses paired by nearest stamp
/// within `max_dt_s` (as evo does), then ATE after SE(2) alignment (without `align`: in the
/// frame both are in). num_poses = 0 when fewer than two pairs.
AteResult TrajectoryError(const std::vector<std::pair<TimestampNs, Pose2>>& estimate,
                          const std::vector<OdometrySample>& reference, double max_dt_s = 0.01,
                          bool align = true);

/// Peak resident memory of this process so far, in MiB.
double PeakMemoryMiB();

}  // namespace uwbsar::slam
