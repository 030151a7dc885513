// The Kobuki base as a LinkProtocol: packets -> basic sensor data -> tick odometry
// (kobuki_odometry.h), handed to the sink on the reading thread. The base streams
// on its own, no start command. Checksum errors, garbage and odometry jumps are
// reported to the FaultLog with counts. The odometry survives reconnects: ticks
// counted while the cable was out are integrated on the first packet back.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "drivers/live/device_link.h"
#include "drivers/live/kobuki_odometry.h"
#include "slam/config.h"

namespace uwbsar::live {

class KobukiDriver : public LinkProtocol {
 public:
  using OdometrySink = std::function<void(OdometrySample&& sample)>;

  KobukiDriver(const LiveConfig& config, FaultLog* faults, std::function<TimestampNs()> clock,
               OdometrySink sink);

  void OnBytes(const std::uint8_t* data, std::size_t size) override;
  void OnLost() override { decoder_.Reset(); }

  const KobukiStats& stats() const { return decoder_.stats(); }
  long long jumps() const { return odometry_.jumps(); }

 private:
  FaultLog* faults_;
  std::function<TimestampNs()> clock_;
  OdometrySink sink_;
  KobukiPacketDecoder decoder_;
  KobukiOdometry odometry_;
  KobukiStats reported_;
  long long reported_jumps_ = 0;
  std::vector<KobukiBasicSensorData> data_;
};

KobukiGeometry GeometryFromConfig(const LiveConfig& config);

}  // namespace uwbsar::live
