// A ROS 2 bag as a MessageSource: radar scans, odometry and ground truth of the
// configured topics (robot_bag.h), in the bag's receive-time order.
#pragma once

#include "core/message.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/robot_bag.h"

namespace uwbsar::rosbag {

class BagSource : public MessageSource {
 public:
  /// Reads from `reader` (an open bag, read once), which must outlive Run().
  BagSource(BagReader& reader, const RobotBagOptions& options)
      : reader_(reader), options_(options) {}
  void Run(const MessageSink& sink) override;
  /// What Run() read, by message type.
  const RobotBagStats& stats() const { return stats_; }

 private:
  BagReader& reader_;
  RobotBagOptions options_;
  RobotBagStats stats_;
};

}  // namespace uwbsar::rosbag
