#include "drivers/live/lt102_protocol.h"

#include <gtest/gtest.h>

#include <cmath>

namespace uwbsar::live {
namespace {

std::vector<std::uint8_t> Frame(std::uint8_t code, const std::vector<std::uint8_t>& payload) {
  std::vector<std::uint8_t> out;
  EncodeLt102Frame(code, payload.data(), payload.size(), &out);
  return out;
}

TEST(Lt102FrameTest, SpecialBytesAreEscapedAndRoundTrip) {
  const std::vector<std::uint8_t> payload = {0xFF, 0x00, 0x80, 0x01, 0xFE, 0x81, 0x42};
  const auto bytes = Frame(0x52, payload);
  // Start and end bytes appear only at the ends.
  EXPECT_EQ(bytes.front(), 0xFF);
  EXPECT_EQ(bytes.back(), 0x00);
  for (std::size_t k = 1; k + 1 < bytes.size(); ++k) {
    EXPECT_NE(bytes[k], 0xFF);
    EXPECT_NE(bytes[k], 0x00);
  }
  EXPECT_EQ(bytes.size(), 2 + 1 + payload.size() + 3);  // three escapes
  Lt102FrameDecoder decoder;
  std::vector<Lt102Frame> frames;
  decoder.Push(bytes.data(), bytes.size(), &frames);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].code, 0x52);
  EXPECT_EQ(frames[0].payload, payload);
}

TEST(Lt102FrameTest, ResynchronisesOnTheNextFrameAfterGarbageAndBrokenFrames) {
  std::vector<std::uint8_t> stream = {0x12, 0x34, 0x56};  // garbage
  auto truncated = Frame(0x52, {1, 2, 3, 4});
  truncated.resize(3);  // no end byte
  stream.insert(stream.end(), truncated.begin(), truncated.end());
  const auto good = Frame(0x52, {9, 8, 7});
  stream.insert(stream.end(), good.begin(), good.end());
  const std::vector<std::uint8_t> bad_escape = {0xFF, 0x52, 0x80, 0x42, 0x01, 0x00};
  stream.insert(stream.end(), bad_escape.begin(), bad_escape.end());
  stream.insert(stream.end(), good.begin(), good.end());
  Lt102FrameDecoder decoder;
  std::vector<Lt102Frame> frames;
  // Byte by byte: the decoder must not depend on how reads split the stream.
  for (std::uint8_t b : stream) decoder.Push(&b, 1, &frames);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].payload, (std::vector<std::uint8_t>{9, 8, 7}));
  EXPECT_EQ(decoder.stats().broken_frames, 2);
  EXPECT_EQ(decoder.stats().garbage_bytes, 3 + 2);  // leading garbage + bytes after the bad escape
}

TEST(Lt102RawDataTest, EveryFormatRoundTripsWithinItsPrecision) {
  std::vector<float> i, q;
  for (int k = 0; k < 64; ++k) {
    i.push_back(0.9f * std::sin(0.3f * static_cast<float>(k)));
    q.push_back(-0.5f * std::cos(0.2f * static_cast<float>(k)));
  }
  const double tolerance[6] = {1.0 / 128, 1.0 / 32768, 1e-8, 0.0, 1e-3, 1e-3};
  for (int format = 0; format <= 5; ++format) {
    const auto payload = EncodeLt102RawData(format, 32, 1234, i, q);
    EXPECT_EQ(payload.size(), 6 + 64 * 2 * static_cast<std::size_t>(Lt102BytesPerValue(format)));
    Lt102RawData raw;
    std::string error;
    ASSERT_TRUE(DecodeLt102RawData(payload.data(), payload.size(), &raw, &error)) << error;
    EXPECT_EQ(raw.format, format);
    EXPECT_EQ(raw.elapsed_us, 1234);
    EXPECT_EQ(raw.samples_per_scan, 32);
    EXPECT_EQ(raw.channels, 2);
    for (std::size_t k = 0; k < i.size(); ++k) {
      EXPECT_NEAR(raw.i[k], i[k], tolerance[format]) << "format " << format;
      EXPECT_NEAR(raw.q[k], q[k], tolerance[format]) << "format " << format;
    }
  }
}

TEST(Lt102RawDataTest, RejectsPayloadSizeMismatchAndBadHeaders) {
  const std::vector<float> i(10, 0.25f), q(10, 0.0f);
  auto payload = EncodeLt102RawData(1, 10, 0, i, q);
  Lt102RawData raw;
  std::string error;
  payload.pop_back();
  EXPECT_FALSE(DecodeLt102RawData(payload.data(), payload.size(), &raw, &error));
  EXPECT_NE(error.find("expected 40"), std::string::npos) << error;
  auto bad_format = EncodeLt102RawData(1, 10, 0, i, q);
  bad_format[3] = static_cast<std::uint8_t>((bad_format[3] & 0x0F) | 0x70);  // format 7
  EXPECT_FALSE(DecodeLt102RawData(bad_format.data(), bad_format.size(), &raw, &error));
  EXPECT_NE(error.find("format 7"), std::string::npos) << error;
  auto not_multiple = EncodeLt102RawData(1, 3, 0, i, q);  // 10 samples, 3 per scan
  EXPECT_FALSE(DecodeLt102RawData(not_multiple.data(), not_multiple.size(), &raw, &error));
  EXPECT_FALSE(DecodeLt102RawData(payload.data(), 4, &raw, &error));
}

TEST(Lt102CrcTest, CrcOverBodyAndItsCrcIsZeroForAnyInit) {
  const std::vector<std::uint8_t> body = {0x01, 0x34, 0x12, 0x66, 0x00, 0xFF, 0x80};
  for (const int init_value : {0x00, 0xFF, 0x5A}) {
    const auto init = static_cast<std::uint8_t>(init_value);
    std::vector<std::uint8_t> with = body;
    with.push_back(Lt102Crc8(body.data(), body.size(), 0x07, init));
    EXPECT_EQ(Lt102Crc8(with.data(), with.size(), 0x07, init), 0);
    with[2] ^= 0x10;  // one flipped bit is caught
    EXPECT_NE(Lt102Crc8(with.data(), with.size(), 0x07, init), 0);
  }
  // CRC-8/SMBUS check value ("123456789" -> 0xF4) with the default polynomial and init.
  const std::string check = "123456789";
  EXPECT_EQ(Lt102Crc8(reinterpret_cast<const std::uint8_t*>(check.data()), check.size(), 0x07, 0),
            0xF4);
}

}  // namespace
}  // namespace uwbsar::live
