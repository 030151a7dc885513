#include "drivers/live/lt102_protocol.h"

#include <opencv2/core/cvdef.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace uwbsar::live {
namespace {

constexpr std::uint8_t kStart = 0xFF, kEnd = 0x00, kEscape = 0x80;

std::int16_t ReadI16(const std::uint8_t* p) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] | (p[1] << 8)));
}
void PutI16(std::vector<std::uint8_t>* out, int v) {
  const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
  out->push_back(static_cast<std::uint8_t>(u & 0xFF));
  out->push_back(static_cast<std::uint8_t>(u >> 8));
}
template <class T>
T ReadLe(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));  // the link and every supported host are little-endian
  return v;
}
template <class T>
void PutLe(std::vector<std::uint8_t>* out, T v) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out->insert(out->end(), b, b + sizeof(T));
}
template <class T>
T Quantize(float v, double scale) {
  const double lo = static_cast<double>(std::numeric_limits<T>::min());
  const double hi = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(std::clamp(std::round(static_cast<double>(v) * scale), lo, hi));
}

float DecodeValue(const std::uint8_t* p, int format) {
  switch (static_cast<Lt102Format>(format)) {
    case Lt102Format::kQ7:
      return static_cast<float>(static_cast<std::int8_t>(p[0])) / 128.0f;
    case Lt102Format::kQ15:
      return static_cast<float>(ReadI16(p)) / 32768.0f;
    case Lt102Format::kQ31:
      return static_cast<float>(static_cast<double>(ReadLe<std::int32_t>(p)) / 2147483648.0);
    case Lt102Format::kFloat32:
      return ReadLe<float>(p);
    case Lt102Format::kFloat16:
    case Lt102Format::kComplexFloat16:
      return static_cast<float>(cv::float16_t::fromBits(ReadLe<std::uint16_t>(p)));
  }
  return 0.0f;
}

void EncodeValue(float v, int format, std::vector<std::uint8_t>* out) {
  switch (static_cast<Lt102Format>(format)) {
    case Lt102Format::kQ7:
      out->push_back(static_cast<std::uint8_t>(Quantize<std::int8_t>(v, 128.0)));
      return;
    case Lt102Format::kQ15:
      PutLe(out, Quantize<std::int16_t>(v, 32768.0));
      return;
    case Lt102Format::kQ31:
      PutLe(out, Quantize<std::int32_t>(v, 2147483648.0));
      return;
    case Lt102Format::kFloat32:
      PutLe(out, v);
      return;
    case Lt102Format::kFloat16:
    case Lt102Format::kComplexFloat16:
      PutLe(out, cv::float16_t(v).bits());
      return;
  }
}

}  // namespace

void Lt102FrameDecoder::Broken(State next) {
  ++stats_.broken_frames;
  body_.clear();
  state_ = next;
}

void Lt102FrameDecoder::Push(const std::uint8_t* data, std::size_t size,
                             std::vector<Lt102Frame>* frames) {
  for (std::size_t k = 0; k < size; ++k) {
    const std::uint8_t b = data[k];
    if (b == kStart) {
      // A start byte is never escaped: it always begins a frame, abandoning a partial one.
      if (state_ != State::kHunt) Broken(State::kInFrame);
      body_.clear();
      state_ = State::kInFrame;
      continue;
    }
    switch (state_) {
      case State::kHunt:
        ++stats_.garbage_bytes;
        break;
      case State::kInFrame:
        if (b == kEnd) {
          if (body_.empty()) {
            Broken(State::kHunt);
            break;
          }
          Lt102Frame frame;
          frame.code = body_[0];
          frame.payload.assign(body_.begin() + 1, body_.end());
          frames->push_back(std::move(frame));
          ++stats_.frames;
          body_.clear();
          state_ = State::kHunt;
        } else if (b == kEscape) {
          state_ = State::kEscape;
        } else {
          body_.push_back(b);
        }
        break;
      case State::kEscape:
        if (b == 0xFE) {
          body_.push_back(0xFF);
        } else if (b == 0x01) {
          body_.push_back(0x00);
        } else if (b == 0x81) {
          body_.push_back(0x80);
        } else {
          Broken(State::kHunt);
          break;
        }
        state_ = State::kInFrame;
        break;
    }
    if (body_.size() > max_frame_bytes_) Broken(State::kHunt);
  }
}

void EncodeLt102Frame(std::uint8_t code, const std::uint8_t* payload, std::size_t size,
                      std::vector<std::uint8_t>* out) {
  out->push_back(kStart);
  auto put = [out](std::uint8_t b) {
    if (b == 0xFF) {
      out->push_back(kEscape), out->push_back(0xFE);
    } else if (b == 0x00) {
      out->push_back(kEscape), out->push_back(0x01);
    } else if (b == 0x80) {
      out->push_back(kEscape), out->push_back(0x81);
    } else {
      out->push_back(b);
    }
  };
  put(code);
  for (std::size_t k = 0; k < size; ++k) put(payload[k]);
  out->push_back(kEnd);
}

int Lt102BytesPerValue(int format) {
  switch (format) {
    case 0:
      return 1;
    case 1:
      return 2;
    case 2:
      return 4;
    case 3:
      return 4;
    case 4:
      return 2;
    case 5:
      return 2;
    default:
      return 0;
  }
}

bool DecodeLt102RawData(const std::uint8_t* payload, std::size_t size, Lt102RawData* out,
                        std::string* error) {
  if (size < 6) {
    *error =
        "raw-data message of " + std::to_string(size) + " bytes: shorter than its 6-byte header";
    return false;
  }
  const int samples_per_scan = ReadI16(payload);
  const auto time_format = static_cast<std::uint16_t>(ReadI16(payload + 2));
  const int total = ReadI16(payload + 4);
  const int format = time_format >> 12;
  if (samples_per_scan <= 0) {
    *error = "raw-data samples_per_scan " + std::to_string(samples_per_scan) + " must be > 0";
    return false;
  }
  if (total <= 0 || total % samples_per_scan != 0) {
    *error = "raw-data total_samples " + std::to_string(total) +
             " must be a positive multiple of samples_per_scan " + std::to_string(samples_per_scan);
    return false;
  }
  const int bytes = Lt102BytesPerValue(format);
  if (bytes == 0) {
    *error = "raw-data sample format " + std::to_string(format) + " is unknown (0..5)";
    return false;
  }
  const std::size_t expected =
      static_cast<std::size_t>(total) * 2 * static_cast<std::size_t>(bytes);
  if (size - 6 != expected) {
    *error = "raw-data payload of " + std::to_string(size - 6) + " bytes, expected " +
             std::to_string(expected) + " (" + std::to_string(total) + " I/Q pairs of format " +
             std::to_string(format) + ")";
    return false;
  }
  out->samples_per_scan = samples_per_scan;
  out->total_samples = total;
  out->channels = total / samples_per_scan;
  out->format = format;
  out->elapsed_us = time_format & 0x0FFF;
  out->i.resize(static_cast<std::size_t>(total));
  out->q.resize(static_cast<std::size_t>(total));
  const std::uint8_t* p = payload + 6;
  for (int k = 0; k < total; ++k) {
    out->i[static_cast<std::size_t>(k)] = DecodeValue(p, format);
    out->q[static_cast<std::size_t>(k)] = DecodeValue(p + bytes, format);
    p += 2 * bytes;
  }
  return true;
}

std::vector<std::uint8_t> EncodeLt102RawData(int format, int samples_per_scan, int elapsed_us,
                                             const std::vector<float>& i,
                                             const std::vector<float>& q) {
  std::vector<std::uint8_t> out;
  const int total = static_cast<int>(i.size());
  PutI16(&out, samples_per_scan);
  PutI16(&out, static_cast<int>(static_cast<std::int16_t>(
                   static_cast<std::uint16_t>(((format & 0xF) << 12) | (elapsed_us & 0x0FFF)))));
  PutI16(&out, total);
  out.reserve(6 + i.size() * 2 * static_cast<std::size_t>(Lt102BytesPerValue(format)));
  for (std::size_t k = 0; k < i.size(); ++k) {
    EncodeValue(i[k], format, &out);
    EncodeValue(k < q.size() ? q[k] : 0.0f, format, &out);
  }
  return out;
}

std::uint8_t Lt102Crc8(const std::uint8_t* data, std::size_t size, std::uint8_t polynomial,
                       std::uint8_t init) {
  std::uint8_t crc = init;
  for (std::size_t k = 0; k < size; ++k) {
    crc ^= data[k];
    for (int bit = 0; bit < 8; ++bit) {
      crc = static_cast<std::uint8_t>((crc & 0x80) ? (crc << 1) ^ polynomial : crc << 1);
    }
  }
  return crc;
}

}  // namespace uwbsar::live
