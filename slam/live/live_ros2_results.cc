#include "slam/live/live_ros2_results.h"

#include <filesystem>

#include "imaging/occupancy_grid.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

LiveResultPublisher::LiveResultPublisher(dds::Participant& participant, const DdsConfig& config,
                                         live::FaultLog* faults, Processor* processor)
    : faults_(faults), processor_(processor), publisher_(participant, config) {
  processor->set_hooks({[this](const MapState& state, const MapOutputs& outputs) {
                          PublishSnapshot(state, outputs);
                        },
                        [this] { PublishPose(false); },
                        [this](const LocalizeRun& run) { PublishLocalized(run); },
                        [this] { PublishPose(true); }});
}

// Snapshot thread: what was just written to disk (from `state`), to RViz2.
void LiveResultPublisher::PublishSnapshot(const MapState& state, const MapOutputs& outputs) {
  try {
    const TimestampNs stamp = state.last_stamp_ns;
    for (const std::string& file : outputs.files) {  // map.yaml, as written
      if (std::filesystem::path(file).filename() == "map.yaml") {
        publisher_.PublishMap(LoadOccupancyGrid(file), stamp);
      }
    }
    publisher_.PublishPath(stamp, state.slam.CorrectedTrajectory());
    publisher_.PublishLoops(stamp, state.slam.AcceptedLoopSegments());
  } catch (const std::exception& e) {
    faults_->Report("ros2: publishing failed", e.what());
  }
}

// Snapshot thread, localising in a saved map: the trajectory in the map frame.
void LiveResultPublisher::PublishLocalized(const LocalizeRun& run) {
  try {
    const auto trajectory = run.Trajectory(false);
    if (!trajectory.empty()) publisher_.PublishPath(trajectory.back().first, trajectory);
  } catch (const std::exception& e) {
    faults_->Report("ros2: publishing failed", e.what());
  }
}

// Snapshot thread: the corrected robot pose, at most every dds.publish_pose_period_s
// (localising: from the first fix on, with the latest fix's correction). `final`: once at
// the end of the run, with the final correction, whatever was published before.
void LiveResultPublisher::PublishPose(bool final) {
  const std::optional<OdometrySample> odom = processor_->LatestOdometry();
  if (!odom || (!final && odom->stamp_ns == last_pose_stamp_ns_)) return;
  const std::optional<Pose2> correction = processor_->CorrectionAt(odom->stamp_ns);
  if (!correction) return;
  last_pose_stamp_ns_ = odom->stamp_ns;
  try {
    if (publisher_.PublishPose(odom->stamp_ns, *correction * odom->T_world_robot, final)) {
      publisher_.PublishMapToOdom(odom->stamp_ns, *correction);
    }
  } catch (const std::exception& e) {
    faults_->Report("ros2: publishing failed", e.what());
  }
}

SerialModePublishing MaybePublishInSerialMode(const Config& config, live::FaultLog* faults,
                                              Processor* processor) {
  SerialModePublishing out;
  if (!config.dds.publish_in_serial_mode) return out;
  out.participant = std::make_unique<dds::Participant>(config.dds);
  out.publisher =
      std::make_unique<LiveResultPublisher>(*out.participant, config.dds, faults, processor);
  return out;
}

}  // namespace uwbsar::slam
