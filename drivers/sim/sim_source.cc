#include "drivers/sim/sim_source.h"

namespace uwbsar::sim {

bool ToMessage(const SimMessage& msg, Message* out) {
  out->stamp_ns = msg.stamp_ns;
  switch (msg.kind) {
    case SimMessage::Kind::kGroundTruth:
      out->kind = Message::Kind::kGroundTruth;
      out->odometry = msg.pose;
      return true;
    case SimMessage::Kind::kOdometry:
      out->kind = Message::Kind::kOdometry;
      out->odometry = msg.pose;
      return true;
    case SimMessage::Kind::kRadarScan:
      out->kind = Message::Kind::kRadarScan;
      out->scan = msg.scan;
      return true;
    case SimMessage::Kind::kLaserScan:
      break;
  }
  return false;
}

void SimSource::Run(const MessageSink& sink) {
  SimMessage msg;
  Message out;
  while (stream_.Next(&msg)) {
    if (!ToMessage(msg, &out)) continue;
    if (T_odom_world_ && out.kind == Message::Kind::kOdometry) {
      out.odometry.T_world_robot = *T_odom_world_ * out.odometry.T_world_robot;
    }
    sink(out);
  }
}

}  // namespace uwbsar::sim
