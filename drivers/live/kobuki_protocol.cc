#include "drivers/live/kobuki_protocol.h"

namespace uwbsar::live {
namespace {
constexpr std::uint8_t kHeader0 = 0xAA, kHeader1 = 0x55;
constexpr std::uint8_t kBasicSensorData = 0x01, kBasicSensorDataLength = 15;

std::uint16_t U16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
}  // namespace

void KobukiPacketDecoder::Push(const std::uint8_t* data, std::size_t size,
                               std::vector<KobukiBasicSensorData>* out) {
  buffer_.insert(buffer_.end(), data, data + size);
  std::size_t pos = 0;
  while (true) {
    // Find a header.
    std::size_t start = pos;
    while (start + 1 < buffer_.size() &&
           !(buffer_[start] == kHeader0 && buffer_[start + 1] == kHeader1)) {
      ++start;
    }
    stats_.garbage_bytes += static_cast<long long>(start - pos);
    pos = start;
    if (pos + 3 > buffer_.size()) break;  // need header + length
    const std::size_t length = buffer_[pos + 2];
    if (pos + 3 + length + 1 > buffer_.size()) break;  // wait for the rest
    std::uint8_t checksum = 0;
    for (std::size_t k = pos + 2; k < pos + 3 + length; ++k) checksum ^= buffer_[k];
    if (checksum != buffer_[pos + 3 + length]) {
      ++stats_.checksum_errors;
      pos += 1;  // resynchronise on the next header, which may lie inside this packet
      continue;
    }
    ++stats_.packets;
    ParsePayload(buffer_.data() + pos + 3, length, out);
    pos += 3 + length + 1;
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(pos));
}

void KobukiPacketDecoder::ParsePayload(const std::uint8_t* p, std::size_t n,
                                       std::vector<KobukiBasicSensorData>* out) {
  std::size_t k = 0;
  while (k + 2 <= n) {
    const std::uint8_t id = p[k];
    const std::size_t len = p[k + 1];
    if (k + 2 + len > n) {
      ++stats_.malformed;
      return;
    }
    const std::uint8_t* d = p + k + 2;
    if (id == kBasicSensorData) {
      if (len < kBasicSensorDataLength) {
        ++stats_.malformed;
      } else {
        KobukiBasicSensorData s;
        s.timestamp_ms = U16(d);
        s.bumper = d[2];
        s.wheel_drop = d[3];
        s.cliff = d[4];
        s.left_encoder = U16(d + 5);
        s.right_encoder = U16(d + 7);
        s.left_pwm = static_cast<std::int8_t>(d[9]);
        s.right_pwm = static_cast<std::int8_t>(d[10]);
        s.button = d[11];
        s.charger = d[12];
        s.battery = d[13];
        s.overcurrent = d[14];
        out->push_back(s);
        ++stats_.sensor_data;
      }
    }
    k += 2 + len;
  }
  if (k != n) ++stats_.malformed;
}

std::vector<std::uint8_t> EncodeKobukiPacket(const KobukiBasicSensorData& s) {
  std::vector<std::uint8_t> payload = {kBasicSensorData,
                                       kBasicSensorDataLength,
                                       static_cast<std::uint8_t>(s.timestamp_ms & 0xFF),
                                       static_cast<std::uint8_t>(s.timestamp_ms >> 8),
                                       s.bumper,
                                       s.wheel_drop,
                                       s.cliff,
                                       static_cast<std::uint8_t>(s.left_encoder & 0xFF),
                                       static_cast<std::uint8_t>(s.left_encoder >> 8),
                                       static_cast<std::uint8_t>(s.right_encoder & 0xFF),
                                       static_cast<std::uint8_t>(s.right_encoder >> 8),
                                       static_cast<std::uint8_t>(s.left_pwm),
                                       static_cast<std::uint8_t>(s.right_pwm),
                                       s.button,
                                       s.charger,
                                       s.battery,
                                       s.overcurrent};
  std::vector<std::uint8_t> out;
  out.reserve(payload.size() + 4);
  out.push_back(kHeader0);
  out.push_back(kHeader1);
  out.push_back(static_cast<std::uint8_t>(payload.size()));
  std::uint8_t checksum = out[2];
  for (std::uint8_t b : payload) {
    checksum ^= b;
    out.push_back(b);
  }
  out.push_back(checksum);
  return out;
}

}  // namespace uwbsar::live
