#include "drivers/live/lt102_driver.h"

namespace uwbsar::live {

Lt102Driver::Lt102Driver(std::string name, int sensor_id, const LiveConfig& config,
                         FaultLog* faults, ScanSink sink)
    : name_(std::move(name)),
      sensor_id_(sensor_id),
      raw_code_(config.lt102_raw_data_code),
      channel_(config.lt102_channel),
      faults_(faults),
      sink_(std::move(sink)) {
  for (const auto& c : config.lt102_start_commands) start_.push_back(ParseLt102Command(c));
  for (const auto& c : config.lt102_stop_commands) stop_.push_back(ParseLt102Command(c));
}

bool Lt102Driver::SendAll(SerialPort& port, const std::vector<Lt102Frame>& commands) {
  std::vector<std::uint8_t> bytes;
  for (const Lt102Frame& c : commands) {
    bytes.clear();
    EncodeLt102Frame(c.code, c.payload.data(), c.payload.size(), &bytes);
    if (!port.Write(bytes.data(), bytes.size(), 0.5)) return false;
  }
  return true;
}

bool Lt102Driver::OnOpen(SerialPort& port) {
  decoder_.Reset();
  return SendAll(port, start_);
}

void Lt102Driver::OnStop(SerialPort& port) { SendAll(port, stop_); }

void Lt102Driver::OnBytes(const std::uint8_t* data, std::size_t size) {
  frames_.clear();
  decoder_.Push(data, size, &frames_);
  const Lt102FrameStats& s = decoder_.stats();
  faults_->Report(name_ + ": garbage bytes", "bytes outside frames skipped",
                  s.garbage_bytes - reported_.garbage_bytes);
  faults_->Report(name_ + ": broken frames", "frames dropped, resynchronised on the next 0xFF",
                  s.broken_frames - reported_.broken_frames);
  reported_ = s;
  for (const Lt102Frame& frame : frames_) {
    if (frame.code != raw_code_) {
      faults_->Report(name_ + ": other frames",
                      "frames with command code " + std::to_string(frame.code) + " ignored");
      continue;
    }
    std::string error;
    if (!DecodeLt102RawData(frame.payload.data(), frame.payload.size(), &raw_, &error)) {
      faults_->Report(name_ + ": invalid raw-data messages", error);
      continue;
    }
    if (channel_ >= raw_.channels) {
      faults_->Report(name_ + ": missing channel",
                      "live.lt102_channel " + std::to_string(channel_) + " but the scan has " +
                          std::to_string(raw_.channels) + " channels");
      continue;
    }
    RadarScan scan;
    scan.sensor_id = sensor_id_;
    const auto begin =
        raw_.i.begin() + static_cast<std::ptrdiff_t>(channel_) * raw_.samples_per_scan;
    scan.samples.assign(begin, begin + raw_.samples_per_scan);
    ++scans_;
    sink_(std::move(scan));
  }
}

}  // namespace uwbsar::live
