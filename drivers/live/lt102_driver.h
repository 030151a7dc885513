// The LT102 as a LinkProtocol: on open it sends the configured start commands, then
// turns raw-data frames into RadarScans (the I samples of the configured channel;
// the link's elapsed-time field is kept for diagnostics) and hands them to the sink
// on the reading thread; the sink stamps them on the host clock. Broken frames,
// garbage bytes, invalid raw-data messages and frames of other codes are reported to
// the FaultLog with counts, never passed on.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "drivers/live/device_link.h"
#include "drivers/live/lt102_protocol.h"
#include "slam/config.h"
#include "slam/types.h"

namespace uwbsar::live {

class Lt102Driver : public LinkProtocol {
 public:
  using ScanSink = std::function<void(RadarScan&& scan)>;

  /// `name` labels faults (e.g. "radar left"). Throws std::invalid_argument on bad commands.
  Lt102Driver(std::string name, int sensor_id, const LiveConfig& config, FaultLog* faults,
              ScanSink sink);

  bool OnOpen(SerialPort& port) override;
  void OnBytes(const std::uint8_t* data, std::size_t size) override;
  void OnStop(SerialPort& port) override;
  void OnLost() override { decoder_.Reset(); }

  long long scans() const { return scans_; }
  const Lt102FrameStats& frame_stats() const { return decoder_.stats(); }

 private:
  bool SendAll(SerialPort& port, const std::vector<Lt102Frame>& commands);

  std::string name_;
  int sensor_id_;
  int raw_code_;
  int channel_;
  std::vector<Lt102Frame> start_, stop_;
  FaultLog* faults_;
  ScanSink sink_;
  Lt102FrameDecoder decoder_;
  Lt102FrameStats reported_;
  std::vector<Lt102Frame> frames_;
  Lt102RawData raw_;
  long long scans_ = 0;
};

}  // namespace uwbsar::live
