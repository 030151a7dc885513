// The Kobuki base as a LinkProtocol: packets -> basic sensor data -> tick odometry
// (kobuki_odometry.h), handed to the sink on the reading thread. The base streams
// on its own, no start command. Checksum errors, garbage and odometry jumps are
// reported to the FaultLog with counts. The odometry survives reconnects: ticks
// counted while the cable was out are integrated on the first packet back.
// Stamps: the base's own millisecond counter (16 bits, unwrapped) through a StreamClock
// (stream_clock.h): each packet is stamped on the lower envelope of its arrivals against
// that counter, not at its arrival, so a reading thread the scheduler delays does not
// move the stamp; re-anchored on reconnect and when the counter restarts.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "drivers/live/device_link.h"
#include "drivers/live/kobuki_odometry.h"
#include "drivers/live/live_config.h"
#include "drivers/live/stream_clock.h"

namespace uwbsar::live {

class KobukiDriver : public LinkProtocol {
 public:
  using OdometrySink = std::function<void(OdometrySample&& sample)>;

  KobukiDriver(const LiveConfig& config, FaultLog* faults, std::function<TimestampNs()> clock,
               OdometrySink sink);

  void OnBytes(const std::uint8_t* data, std::size_t size) override;
  void OnLost() override {
    decoder_.Reset();
    stamps_.Reset();
    have_ms_ = false;
  }
  const StreamClock& stamp_clock() const { return stamps_; }

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
  StreamClock stamps_;
  bool have_ms_ = false;
  std::uint16_t last_ms_ = 0;
  std::int64_t device_ms_ = 0;  ///< the counter unwrapped
};

KobukiGeometry GeometryFromConfig(const LiveConfig& config);

}  // namespace uwbsar::live
