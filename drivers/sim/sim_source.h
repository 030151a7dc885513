// The simulator as a MessageSource: the SimStream of a scenario with laser scans left
// out (they are for recordings; SLAM does not use them).
#pragma once

#include <cstdint>

#include "drivers/sim/sim_stream.h"
#include "slam/message.h"

namespace uwbsar::sim {

/// `msg` as a Message; false for a laser scan, which has no Message kind.
bool ToMessage(const SimMessage& msg, Message* out);

class SimSource : public MessageSource {
 public:
  SimSource(const SimSettings& config, const SimScenario& scenario, std::uint64_t seed)
      : stream_(config, scenario, seed) {}
  void Run(const MessageSink& sink) override;

 private:
  SimStream stream_;
};

}  // namespace uwbsar::sim
