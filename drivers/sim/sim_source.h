// The simulator as a MessageSource: the SimStream of a scenario with laser scans left
// out (they are for recordings; SLAM does not use them).
#pragma once

#include <cstdint>
#include <optional>

#include "core/message.h"
#include "drivers/sim/sim_stream.h"

namespace uwbsar::sim {

/// `msg` as a Message; false for a laser scan, which has no Message kind.
bool ToMessage(const SimMessage& msg, Message* out);

class SimSource : public MessageSource {
 public:
  /// With `T_odom_world`, the wheel odometry is reported in a frame of its own:
  /// T_odom_world * (the simulator's odometry, which starts at the true start pose); the
  /// ground truth stays in the world (map file) frame. Without it, odometry is as simulated.
  SimSource(const SimSettings& config, const SimScenario& scenario, std::uint64_t seed,
            std::optional<Pose2> T_odom_world = std::nullopt)
      : stream_(config, scenario, seed), T_odom_world_(T_odom_world) {}
  void Run(const MessageSink& sink) override;

 private:
  SimStream stream_;
  std::optional<Pose2> T_odom_world_;
};

}  // namespace uwbsar::sim
