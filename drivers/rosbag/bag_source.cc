#include "drivers/rosbag/bag_source.h"

namespace uwbsar::rosbag {
namespace {

/// The bag reader's callbacks as Messages.
class ToMessages : public RobotBagVisitor {
 public:
  explicit ToMessages(const MessageSink& sink) : sink_(sink) {}
  void OnRadarScan(const RadarScan& scan) override {
    message_.kind = Message::Kind::kRadarScan;
    message_.stamp_ns = scan.stamp_ns;
    message_.scan = scan;
    sink_(message_);
  }
  void OnOdometry(const OdometrySample& odometry) override {
    Pose(Message::Kind::kOdometry, odometry);
  }
  void OnGroundTruth(const OdometrySample& pose) override {
    Pose(Message::Kind::kGroundTruth, pose);
  }

 private:
  void Pose(Message::Kind kind, const OdometrySample& pose) {
    message_.kind = kind;
    message_.stamp_ns = pose.stamp_ns;
    message_.odometry = pose;
    sink_(message_);
  }
  const MessageSink& sink_;
  Message message_;
};

}  // namespace

void BagSource::Run(const MessageSink& sink) {
  ToMessages visitor(sink);
  stats_ = ReadRobotBag(reader_, options_, visitor);
}

}  // namespace uwbsar::rosbag
