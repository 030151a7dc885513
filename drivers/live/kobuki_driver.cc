#include "drivers/live/kobuki_driver.h"

namespace uwbsar::live {

KobukiGeometry GeometryFromConfig(const LiveConfig& config) {
  KobukiGeometry g;
  g.wheel_radius_m = config.kobuki_wheel_radius_m;
  g.wheelbase_m = config.kobuki_wheelbase_m;
  g.ticks_per_revolution = config.kobuki_ticks_per_revolution;
  g.max_wheel_speed_mps = config.max_wheel_speed_mps;
  return g;
}

KobukiDriver::KobukiDriver(const LiveConfig& config, FaultLog* faults,
                           std::function<TimestampNs()> clock, OdometrySink sink)
    : faults_(faults),
      clock_(std::move(clock)),
      sink_(std::move(sink)),
      odometry_(GeometryFromConfig(config)),
      stamps_([] {
        StreamClockOptions o;
        o.nominal_ns_per_unit = 1e6;  // a millisecond counter
        o.gap_units = 2000;           // 2 s without packets: anchor again
        return o;
      }()) {}

void KobukiDriver::OnBytes(const std::uint8_t* data, std::size_t size) {
  data_.clear();
  decoder_.Push(data, size, &data_);
  const KobukiStats& s = decoder_.stats();
  faults_->Report("kobuki: checksum errors", "packets dropped, resynchronised on the next header",
                  s.checksum_errors - reported_.checksum_errors);
  faults_->Report("kobuki: garbage bytes", "bytes outside packets skipped",
                  s.garbage_bytes - reported_.garbage_bytes);
  faults_->Report("kobuki: malformed packets", "sub-payload lengths do not add up",
                  s.malformed - reported_.malformed);
  reported_ = s;
  for (const KobukiBasicSensorData& d : data_) {
    const TimestampNs arrival_ns = clock_();
    // A counter that went back restarts the line (StreamClock re-anchors on x going back).
    const std::uint16_t step = static_cast<std::uint16_t>(d.timestamp_ms - last_ms_);
    device_ms_ = have_ms_ ? device_ms_ + (step < 0x8000 ? step : step - 0x10000) : 0;
    have_ms_ = true;
    last_ms_ = d.timestamp_ms;
    auto sample = odometry_.Update(stamps_.Stamp(device_ms_, arrival_ns), d);
    if (odometry_.jumps() != reported_jumps_) {
      faults_->Report("kobuki: odometry jumps",
                      "encoder step faster than live.max_wheel_speed_mps, not integrated",
                      odometry_.jumps() - reported_jumps_);
      reported_jumps_ = odometry_.jumps();
    }
    if (sample) sink_(std::move(*sample));
  }
}

}  // namespace uwbsar::live
