// Publishes a live run's results for RViz2 over DDS (drivers/dds): at every snapshot the
// map (as just written to map.yaml), the corrected trajectory and the accepted loops; every
// dds.publish_pose_period_s the corrected robot pose and the map -> odom transform on /tf.
// Used by the ros2 source, and with the serial source when dds.publish_in_serial_mode.
// Localising in a saved map (run --localize-in): the localised path at every snapshot and,
// from the first fix on, the localised pose and map -> odom on /tf.
#pragma once

#include <memory>

#include "drivers/dds/participant.h"
#include "drivers/dds/ros2_publisher.h"
#include "drivers/live/fault_log.h"
#include "slam/app_config.h"
#include "slam/live/live_processor.h"

namespace uwbsar::slam {

class LiveResultPublisher {
 public:
  /// Installs itself as `processor`'s snapshot hooks; must outlive the snapshot thread
  /// and the final snapshot. Publishing errors are reported as faults, never thrown.
  LiveResultPublisher(dds::Participant& participant, const DdsConfig& config,
                      live::FaultLog* faults, Processor* processor);

 private:
  void PublishSnapshot(const MapState& state, const MapOutputs& outputs);
  void PublishPose(bool final);
  void PublishLocalized(const LocalizeRun& run);

  live::FaultLog* faults_;
  Processor* processor_;
  dds::Ros2Publisher publisher_;
  TimestampNs last_pose_stamp_ns_ = 0;
};

/// With the serial source and dds.publish_in_serial_mode: a participant and a publisher
/// of the results (else null). Throws InputError / DdsError when DDS cannot start.
struct SerialModePublishing {
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<LiveResultPublisher> publisher;
};
SerialModePublishing MaybePublishInSerialMode(const Config& config, live::FaultLog* faults,
                                              Processor* processor);

}  // namespace uwbsar::slam
