// One message type for every source of robot data (a ROS 2 bag, the simulator, the
// robot's serial devices, a ROS 2 robot over DDS): a radar scan, an odometry sample, a
// ground-truth pose or a run event, with the stamp it is ordered by. Sources emit
// messages in stamp order; the pipeline feeds them to SLAM through one Feed().
#pragma once

#include <functional>
#include <string>

#include "core/types.h"

namespace uwbsar {

struct Message {
  enum class Kind { kRadarScan, kOdometry, kGroundTruth, kEvent };
  Kind kind = Kind::kEvent;
  TimestampNs stamp_ns = 0;  ///< equals scan.stamp_ns or odometry.stamp_ns for those kinds
  RadarScan scan;            ///< kRadarScan; scan.sensor_id indexes Config::radars
  OdometrySample odometry;   ///< kOdometry: wheel odometry; kGroundTruth: the true pose
  std::string text;          ///< kEvent
};

/// Receives a source's messages, one call each, in the source's order.
using MessageSink = std::function<void(const Message&)>;

/// Where messages come from. Run() hands every message to `sink` in stamp order and
/// returns at the end of the source; bad input throws InputError naming it.
class MessageSource {
 public:
  virtual ~MessageSource() = default;
  virtual void Run(const MessageSink& sink) = 0;
};

/// Hands the radar scan or odometry sample in `m` to `consumer`: anything with
/// AddScan(const RadarScan&) and AddOdometry(const OdometrySample&) (the SlamSystem, the
/// imaging frontend, a localiser). Ground truth and events are not theirs: the caller keeps
/// them. The one place a message's kind picks the consumer's call.
template <class Consumer>
void FeedScanOrOdometry(Consumer& consumer, const Message& m) {
  if (m.kind == Message::Kind::kRadarScan) consumer.AddScan(m.scan);
  if (m.kind == Message::Kind::kOdometry) consumer.AddOdometry(m.odometry);
}

}  // namespace uwbsar
