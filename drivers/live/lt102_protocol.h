// The ARIA Sensing LT102 serial link: byte-stuffed frames
// (0xFF, command byte, payload, 0x00; 0xFF, 0x00 and 0x80 inside a frame escaped as
// 0x80 + 0xFE / 0x01 / 0x81) and the raw-data message (little-endian int16
// samples_per_scan, int16 elapsed-time (low 12 bits, us) + format (top 4 bits),
// int16 total_samples, then total_samples I/Q pairs in one of six sample formats).
// The decoder is a byte-stream state machine: garbage between frames is skipped and
// counted, a broken frame (a new 0xFF before the 0x00, an invalid escape, an
// oversized frame) is dropped and counting resumes at the next 0xFF.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace uwbsar::live {

struct Lt102Frame {
  std::uint8_t code = 0;
  std::vector<std::uint8_t> payload;
};

struct Lt102FrameStats {
  long long frames = 0;
  long long garbage_bytes = 0;  ///< bytes outside any frame
  long long broken_frames = 0;  ///< frames dropped: restarted, bad escape, empty, oversized
};

class Lt102FrameDecoder {
 public:
  explicit Lt102FrameDecoder(std::size_t max_frame_bytes = 1 << 20)
      : max_frame_bytes_(max_frame_bytes) {}
  /// Consumes bytes; complete frames are appended to `frames`.
  void Push(const std::uint8_t* data, std::size_t size, std::vector<Lt102Frame>* frames);
  /// Forgets a partial frame (after a reconnect); not counted as broken.
  void Reset() { state_ = State::kHunt; }
  const Lt102FrameStats& stats() const { return stats_; }

 private:
  enum class State { kHunt, kInFrame, kEscape };
  void Broken(State next);
  std::size_t max_frame_bytes_;
  State state_ = State::kHunt;
  std::vector<std::uint8_t> body_;  ///< unstuffed code + payload
  Lt102FrameStats stats_;
};

/// Appends the stuffed frame of `code` + `payload` to `out`.
void EncodeLt102Frame(std::uint8_t code, const std::uint8_t* payload, std::size_t size,
                      std::vector<std::uint8_t>* out);

/// Sample formats of the raw-data message (top 4 bits of its second field).
enum class Lt102Format : int {
  kQ7 = 0,
  kQ15 = 1,
  kQ31 = 2,
  kFloat32 = 3,
  kFloat16 = 4,
  kComplexFloat16 = 5
};
/// Bytes of one I or Q value; 0 for an unknown format.
int Lt102BytesPerValue(int format);

struct Lt102RawData {
  int samples_per_scan = 0;
  int total_samples = 0;
  int channels = 0;  ///< total_samples / samples_per_scan
  int format = 0;
  int elapsed_us = 0;
  std::vector<float> i, q;  ///< total_samples each, channel-major; fixed point scaled to [-1, 1)
};

/// Decodes a raw-data payload. Returns false with `error` set (one line naming the field)
/// when the message is invalid: short header, non-positive sizes, total not a multiple of
/// samples_per_scan, unknown format, or a payload size other than total * 2 * bytes.
bool DecodeLt102RawData(const std::uint8_t* payload, std::size_t size, Lt102RawData* out,
                        std::string* error);

/// The raw-data payload of I/Q values in `format` (fixed point: clamped and rounded).
std::vector<std::uint8_t> EncodeLt102RawData(int format, int samples_per_scan, int elapsed_us,
                                             const std::vector<float>& i,
                                             const std::vector<float>& q);

/// CRC-8 (MSB first, no reflection, no final xor) of `size` bytes. Run over a body and its
/// appended CRC it gives 0, which is how the receiver checks it.
std::uint8_t Lt102Crc8(const std::uint8_t* data, std::size_t size, std::uint8_t polynomial,
                       std::uint8_t init);

}  // namespace uwbsar::live
