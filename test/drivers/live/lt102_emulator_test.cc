// The LT102 emulator's `d` behaviour, driven by hand (no thread): the vendor behaviour
// (answered at once with the latest frame, the same frame again when polled before the next
// one, frames replaced unasked counted missed) and the optional hold-until-next-frame one.
#include "drivers/emulators/lt102_emulator.h"

#include <gtest/gtest.h>

#include <thread>

#include "drivers/live/serial_port.h"
#include "lt102_test_util.h"

namespace uwbsar::live {
namespace {

/// A host end of the emulator's link that sends requests and collects `d` answers.
class Host {
 public:
  explicit Host(Lt102Emulator* radar) : radar_(radar) { port_.Open(radar->link_path(), 115200); }
  void Send(std::uint8_t code) {
    const std::vector<std::uint8_t> bytes = EncodeLt102Body({code}, Lt102CrcMode{});
    ASSERT_TRUE(port_.Write(bytes.data(), bytes.size(), 0.1));
  }
  /// Serves, then reads what came back within `wait_s`: the `d` answers' payloads.
  std::vector<std::vector<std::uint8_t>> Answers(double wait_s = 0.05) {
    std::vector<std::vector<std::uint8_t>> out;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s);
    while (std::chrono::steady_clock::now() < end) {
      radar_->Serve();
      std::uint8_t buffer[65536];
      std::size_t n = 0;
      if (port_.Read(buffer, sizeof(buffer), 0.002, &n) == SerialPort::ReadStatus::kData) {
        std::vector<Lt102Frame> frames;
        decoder_.Push(buffer, n, &frames);
        for (const Lt102Frame& f : frames) {
          if (f.code == lt102::kReadFrame) out.push_back(f.payload);
        }
      }
    }
    return out;
  }

 private:
  Lt102Emulator* radar_;
  SerialPort port_;
  Lt102FrameDecoder decoder_;
};

std::vector<float> Frame(int n) {
  std::vector<float> v = Lt102Ramp();
  v[0] = static_cast<float>(n) / 2000.0f;
  return v;
}

TEST(Lt102EmulatorTest, DIsAnsweredAtOnceWithTheLatestFrameAndRepeatsItWhenPolledEarly) {
  Lt102Emulator radar(Lt102TempLink("emu_vendor"), {});
  Host host(&radar);
  host.Send(lt102::kStart);
  host.Answers();
  ASSERT_TRUE(radar.started());
  host.Send(lt102::kReadFrame);  // before the first frame: waits for it
  EXPECT_TRUE(host.Answers().empty());
  radar.Acquire(Frame(1), 0.0);
  const auto first = host.Answers();
  ASSERT_EQ(first.size(), 1u);
  host.Send(lt102::kReadFrame);  // polled before the next frame: the same frame at once
  const auto again = host.Answers();
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0], first[0]);
  radar.Acquire(Frame(2), 0.0);
  radar.Acquire(Frame(3), 0.0);  // frame 2 replaced unasked: missed
  host.Send(lt102::kReadFrame);
  const auto third = host.Answers();
  ASSERT_EQ(third.size(), 1u);
  EXPECT_NE(third[0], first[0]);
  const Lt102EmulatorCounts c = radar.counts();
  EXPECT_EQ(c.frames_acquired, 3);
  EXPECT_EQ(c.frames_answered, 3);
  EXPECT_EQ(c.frames_repeated, 1);
  EXPECT_EQ(c.frames_overwritten, 1);
  EXPECT_EQ(c.frames_missed, 1);
}

TEST(Lt102EmulatorTest, WithTheHoldOptionAnEarlyDWaitsForTheNextFrame) {
  Lt102EmulatorOptions options;
  options.hold_d_until_next_frame = true;
  Lt102Emulator radar(Lt102TempLink("emu_hold"), options);
  Host host(&radar);
  host.Send(lt102::kStart);
  host.Answers();
  radar.Acquire(Frame(1), 0.0);
  host.Send(lt102::kReadFrame);
  const auto first = host.Answers();
  ASSERT_EQ(first.size(), 1u);
  host.Send(lt102::kReadFrame);  // frame 1 handed out already: held
  EXPECT_TRUE(host.Answers().empty());
  radar.Acquire(Frame(2), 0.0);
  const auto second = host.Answers();
  ASSERT_EQ(second.size(), 1u);
  EXPECT_NE(second[0], first[0]);
  const Lt102EmulatorCounts c = radar.counts();
  EXPECT_EQ(c.frames_answered, 2);
  EXPECT_EQ(c.frames_repeated, 0);
  EXPECT_EQ(c.frames_missed, 0);
}

TEST(Lt102EmulatorTest, AQueryValueIsASettingWhereTheTableDefinesNoQuery) {
  Lt102EmulatorOptions options;
  options.prf_divider = 1;
  Lt102Emulator radar(Lt102TempLink("emu_v"), options);
  SerialPort port;
  port.Open(radar.link_path(), 115200);
  const std::vector<std::uint8_t> v = EncodeLt102Body({lt102::kPrfDivider, 0xFF}, {});
  ASSERT_TRUE(port.Write(v.data(), v.size(), 0.1));
  std::vector<Lt102Frame> frames;
  Lt102FrameDecoder decoder;
  for (int i = 0; i < 50 && frames.empty(); ++i) {
    radar.Serve();
    std::uint8_t buffer[256];
    std::size_t n = 0;
    if (port.Read(buffer, sizeof(buffer), 0.002, &n) == SerialPort::ReadStatus::kData) {
      decoder.Push(buffer, n, &frames);
    }
  }
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(frames[0].payload.size(), 1u);
  EXPECT_EQ(frames[0].payload[0], 0xFF);  // divider set to 255 (i8 -1), as a module would
}

}  // namespace
}  // namespace uwbsar::live
