// The Kobuki (TurtleBot2) base's public serial protocol: packets of
// 0xAA 0x55, a length byte (of the payload), the payload (sub-payloads of
// id, length, data) and a checksum byte (XOR of the length byte and the payload).
// Only the basic sensor data sub-payload (id 0x01, 15 bytes: timestamp ms,
// bumper, wheel drop, cliff, left and right encoder ticks, PWMs, button, charger,
// battery, overcurrent) is decoded; other sub-payloads are skipped by their length.
// A checksum error drops the packet and resynchronises on the next header.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace uwbsar::live {

struct KobukiBasicSensorData {
  std::uint16_t timestamp_ms = 0;  ///< the base's clock, wraps every 65.536 s
  std::uint8_t bumper = 0;
  std::uint8_t wheel_drop = 0;
  std::uint8_t cliff = 0;
  std::uint16_t left_encoder = 0;   ///< ticks, wraps at 65536
  std::uint16_t right_encoder = 0;  ///< ticks, wraps at 65536
  std::int8_t left_pwm = 0;
  std::int8_t right_pwm = 0;
  std::uint8_t button = 0;
  std::uint8_t charger = 0;
  std::uint8_t battery = 0;  ///< 0.1 V
  std::uint8_t overcurrent = 0;
};

struct KobukiStats {
  long long packets = 0;
  long long sensor_data = 0;
  long long checksum_errors = 0;
  long long malformed = 0;      ///< sub-payload lengths not adding up
  long long garbage_bytes = 0;  ///< bytes skipped while looking for a header
};

class KobukiPacketDecoder {
 public:
  void Push(const std::uint8_t* data, std::size_t size, std::vector<KobukiBasicSensorData>* out);
  void Reset() { buffer_.clear(); }
  const KobukiStats& stats() const { return stats_; }

 private:
  void ParsePayload(const std::uint8_t* p, std::size_t n, std::vector<KobukiBasicSensorData>* out);
  std::vector<std::uint8_t> buffer_;
  KobukiStats stats_;
};

/// One packet holding one basic sensor data sub-payload (what the base sends at 50 Hz).
std::vector<std::uint8_t> EncodeKobukiPacket(const KobukiBasicSensorData& data);

}  // namespace uwbsar::live
