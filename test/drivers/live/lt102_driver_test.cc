// The LT102 driver on a reconnecting link against the emulated module: polled `d`
// acquisition (one request in flight, requests vs answers counted), the stop `o` on a
// deliberate stop and before a power cycle, and the faults: a frame of a bad size, a
// missing answer, a wrong echo, an unplug, frames with a CRC byte. Every valid frame that
// arrived is delivered once: against a radar that answers `d` at once with its latest frame
// (the vendor behaviour) and one that holds an early `d`, each frame is delivered once,
// repeats dropped and counted, polls paced at the radar's actual frame rate.
#include "drivers/live/lt102_driver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>

#include "lt102_test_util.h"
#include "slam/app_config.h"

namespace uwbsar::live {
namespace {

struct DriverRun {
  Lt102Stats stats;
  long long scans = 0;
  std::vector<float> first;
  std::vector<float> marks;  ///< sample 0 of every scan: the emulated frame's number
};

/// Runs the driver on `radar` for `seconds` (or until `until` holds), then stops the link.
class DriverHarness {
 public:
  /// `priority`: the link thread's SCHED_FIFO priority (LinkPolicy; 0 = normal).
  explicit DriverHarness(const EmulatedLt102& radar, Config config = {},
                         std::function<void()> power_cycle = {}, int priority = 0)
      : driver_("radar left", 0, config, &faults_, [this](RadarScan&& scan) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (scans_++ == 0) first_ = scan.samples;
          marks_.push_back(scan.samples.empty() ? -1.0f : scan.samples[0]);
        }) {
    LinkPolicy policy;
    policy.reconnect_initial_s = 0.01;
    policy.reconnect_max_s = 0.05;
    policy.realtime_priority = priority;
    link_ = std::make_unique<DeviceLink>("radar left", radar.path(), policy, &driver_, &faults_,
                                         std::move(power_cycle));
    link_->Start();
  }
  DriverRun Stop() {
    link_->Stop();
    DriverRun run;
    run.stats = driver_.stats();
    std::lock_guard<std::mutex> lock(mutex_);
    run.scans = scans_;
    run.first = first_;
    run.marks = marks_;
    return run;
  }
  long long scans() {
    std::lock_guard<std::mutex> lock(mutex_);
    return scans_;
  }
  Lt102Driver& driver() { return driver_; }
  FaultLog& faults() { return faults_; }
  DeviceLink& link() { return *link_; }

 private:
  FaultLog faults_;
  std::mutex mutex_;
  long long scans_ = 0;
  std::vector<float> first_, marks_;
  Lt102Driver driver_;
  std::unique_ptr<DeviceLink> link_;
};

bool EndsWith(const std::vector<std::uint8_t>& bytes, const std::vector<std::uint8_t>& tail) {
  return bytes.size() >= tail.size() &&
         std::equal(tail.begin(), tail.end(), bytes.end() - tail.size());
}

TEST(Lt102DriverTest, PollsOneFrameAtATimeAndStopsTheRadarWithO) {
  EmulatedLt102 radar("poll");
  DriverHarness h(radar);
  ASSERT_TRUE(WaitUntil([&] { return h.scans() >= 100; }));
  const DriverRun run = h.Stop();
  const Lt102EmulatorCounts emulated = radar.counts();
  std::printf(
      "polled: %lld requests, %lld answers, %lld lost; request-to-answer p50 %.2f ms, "
      "p99 %.2f ms; emulator acquired %lld, answered %lld, overwritten %lld\n",
      run.stats.requests, run.stats.answers, run.stats.lost, run.stats.answer_p50_ms,
      run.stats.answer_p99_ms, emulated.frames_acquired, emulated.frames_answered,
      emulated.frames_overwritten);
  EXPECT_EQ(run.stats.lost, 0);
  EXPECT_EQ(run.stats.answers, run.stats.requests);  // the stop waits for the one in flight
  EXPECT_EQ(run.stats.answers, emulated.frames_answered);
  EXPECT_EQ(run.stats.frames_repeated, emulated.frames_repeated);
  EXPECT_EQ(run.scans, run.stats.answers - run.stats.frames_repeated);
  EXPECT_GT(run.stats.answer_p99_ms, 0.0);
  const std::vector<float> ramp = Lt102Ramp();
  ASSERT_EQ(run.first.size(), 1000u);
  EXPECT_NEAR(run.first[999], ramp[999], 1.0 / 32768);  // Q15 by default
  // Stopped with 'o' (answered), the last bytes on the wire. The harness copies the
  // emulator's state after it served the 'o', which may be just after the driver read the
  // answer: wait for it rather than race it.
  EXPECT_TRUE(WaitUntil([&] { return !radar.started(); }));
  EXPECT_EQ(run.stats.stops, 1);
  EXPECT_TRUE(EndsWith(radar.received(), {0xFF, 'o', 0x00}));
}

TEST(Lt102DriverTest, AFrameOfABadSizeIsReportedAndPollingGoesOn) {
  Lt102EmulatorOptions options;
  options.bad_size_every = 5;
  EmulatedLt102 radar("bad_size", options);
  DriverHarness h(radar);
  ASSERT_TRUE(WaitUntil([&] { return h.scans() >= 40; }));
  const DriverRun run = h.Stop();
  const Lt102EmulatorCounts emulated = radar.counts();
  EXPECT_GT(emulated.bad_size_frames, 0);
  EXPECT_EQ(run.stats.invalid_frames, emulated.bad_size_frames);
  EXPECT_EQ(h.faults().Count("radar left: invalid raw-data messages"), emulated.bad_size_frames);
  // The rest arrived, each frame once.
  EXPECT_EQ(run.scans,
            emulated.frames_answered - emulated.bad_size_frames - run.stats.frames_repeated);
  EXPECT_EQ(run.stats.lost, 0);
}

TEST(Lt102DriverTest, AMissingFrameAnswerIsCountedLostAndTheNextRequestGoesOut) {
  Lt102EmulatorOptions options;
  options.missing_answer_code = lt102::kReadFrame;
  options.missing_answer_times = 3;
  EmulatedLt102 radar("missing_d", options);
  DriverHarness h(radar);
  ASSERT_TRUE(WaitUntil([&] { return h.scans() >= 30; }));
  const DriverRun run = h.Stop();
  EXPECT_EQ(run.stats.lost, 3);
  EXPECT_EQ(h.faults().Count("radar left: lost frames"), 3);
  EXPECT_EQ(run.stats.answers, run.stats.requests - 3);
  EXPECT_EQ(run.scans, radar.counts().frames_answered - run.stats.frames_repeated);
}

TEST(Lt102DriverTest, AWrongEchoFailsTheOpenWithAConfigurationErrorAndTheLinkRetries) {
  Lt102EmulatorOptions options;
  options.wrong_echo_code = lt102::kChannel;
  EmulatedLt102 radar("wrong_echo", options);
  DriverHarness h(radar);
  Lt102Setup setup;
  std::string error;
  EXPECT_FALSE(h.driver().WaitConfigured(5.0, &setup, &error));
  EXPECT_EQ(error,
            "radar left: configuration error: data channel ('$' 0x24) sent 0, the radar echoed 1");
  ASSERT_TRUE(WaitUntil([&] { return h.link().counters().open_failures >= 2; }));
  const DriverRun run = h.Stop();
  EXPECT_GE(run.stats.config_errors, 2);
  EXPECT_GE(h.faults().Count("radar left: configuration errors"), 2);
  EXPECT_EQ(run.scans, 0);
}

TEST(Lt102DriverTest, AReconnectRunsTheStartUpAgain) {
  EmulatedLt102 radar("replug");
  DriverHarness h(radar);
  ASSERT_TRUE(WaitUntil([&] { return h.scans() >= 10; }));
  radar.SetPlugged(false);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  radar.SetPlugged(true);
  const long long before = h.scans();
  ASSERT_TRUE(WaitUntil([&] { return h.scans() >= before + 10; }));
  const DriverRun run = h.Stop();
  EXPECT_EQ(run.stats.startups, 2);
  EXPECT_GE(h.faults().Count("radar left: unplugged"), 1);
}

TEST(Lt102DriverTest, TheRadarIsStoppedBeforeItIsPowerCycled) {
  Lt102EmulatorOptions options;
  options.missing_answer_code = lt102::kVersion;  // never starts: the open keeps failing
  options.missing_answer_times = 1000;
  EmulatedLt102 radar("power_cycle", options);
  Config config;
  config.live.lt102.answer_timeout_s = 0.05;
  std::atomic<int> cycles{0};
  std::atomic<bool> stopped_first{false};
  DriverHarness h(radar, config, [&] {
    stopped_first = EndsWith(radar.received(), {0xFF, 'o', 0x00});
    ++cycles;
  });
  ASSERT_TRUE(WaitUntil([&] { return cycles >= 1; }, 10.0));
  const DriverRun run = h.Stop();
  EXPECT_TRUE(stopped_first);
  EXPECT_GE(run.stats.stops, 1);
  EXPECT_GE(h.faults().Count("radar left: cannot connect"), 3);
}

TEST(Lt102DriverTest, FramesWithACrcByteAreCheckedAndDelivered) {
  Lt102EmulatorOptions options;
  options.crc = true;
  EmulatedLt102 radar("crc_frames", options);
  DriverHarness h(radar);
  ASSERT_TRUE(WaitUntil([&] { return h.scans() >= 20; }));
  const DriverRun run = h.Stop();
  EXPECT_TRUE(run.stats.setup.crc);
  EXPECT_EQ(run.stats.invalid_frames, 0);
  // Every valid frame is delivered once: answers, and late answers (past the answer timeout on
  // a busy machine, still valid), less the repeats of a frame already delivered.
  EXPECT_EQ(run.scans, run.stats.answers + run.stats.late_answers - run.stats.frames_repeated);
}

struct PacingCase {
  const char* name;
  bool hold;            ///< the radar holds an early `d` (else: repeats its latest frame)
  int period_ms;        ///< the radar's actual frame period
  int asked_fps;        ///< live.lt102.frame_rate_fps
  int stall_every = 0;  ///< every n-th frame comes a period late with the next (overwritten)
};

void PrintTo(const PacingCase& c, std::ostream* os) { *os << c.name; }

class Lt102PacingTest : public ::testing::TestWithParam<PacingCase> {};

TEST_P(Lt102PacingTest, EachFrameIsDeliveredOnceAndPollsFollowTheRadarsFrameRate) {
  const PacingCase c = GetParam();
  Lt102EmulatorOptions options;
  options.hold_d_until_next_frame = c.hold;
  options.actual_frame_rate_fps = 1000 / c.period_ms;
  // The emulator and the link thread run under SCHED_FIFO, as `uwbsar run` and the emulated
  // runs do (live.driver_priority): at normal priority a busy machine starves the polling
  // (then the rates are printed, not asserted; the counts are checked either way).
  constexpr int kPriority = 20;
  EmulatedLt102 radar(std::string("pacing_") + c.name, options, c.period_ms, c.stall_every,
                      kPriority);
  Config config;
  config.live.lt102.frame_rate_fps = c.asked_fps;
  DriverHarness h(radar, config, {}, kPriority);
  const long long frames = 3000 / c.period_ms;  // 3 s
  ASSERT_TRUE(WaitUntil([&] { return h.scans() >= frames; }, 10.0));
  const DriverRun run = h.Stop();
  const Lt102EmulatorCounts e = radar.counts();
  const double fps = 1000.0 / c.period_ms;
  const double polls_per_s = static_cast<double>(run.stats.requests) / run.stats.acquiring_s;
  std::printf(
      "%s: %d frames/s (%d asked): %lld requests (%.1f/s), %lld frames delivered, %lld "
      "repeated, %lld missed; emulator answered %lld, repeated %lld, missed %lld\n",
      c.name, run.stats.setup.frame_rate_fps, c.asked_fps, run.stats.requests, polls_per_s,
      run.stats.frames_delivered, run.stats.frames_repeated, run.stats.frames_missed,
      e.frames_answered, e.frames_repeated, e.frames_missed);
  EXPECT_EQ(run.stats.setup.frame_rate_fps, static_cast<int>(fps));
  // Every delivered scan is a distinct frame (sample 0 counts the emulated frames).
  for (std::size_t i = 1; i < run.marks.size(); ++i) {
    ASSERT_NE(run.marks[i], run.marks[i - 1]) << "scan " << i << " repeats its predecessor";
  }
  EXPECT_EQ(run.stats.frames_repeated, e.frames_repeated);
  EXPECT_EQ(run.scans, run.stats.frames_delivered);
  // The frame rate, not faster: at least 90 % of it, and at most 20 % more. A poll that wakes
  // late on a busy machine (under ASan: 112 polls/s at 100 frames/s) finds the next frame not
  // yet made and asks again; those answers are counted as repeated and never delivered (the
  // exact-once delivery is asserted above). A radar whose frames come late is asked again until
  // they do (a few polls per late frame, not bounded here).
  if (c.stall_every == 0) {
    EXPECT_GE(polls_per_s, 0.9 * fps);
    EXPECT_LE(polls_per_s, 1.2 * fps);
  }
  // Misses: the driver's count from the frame period and the request times, against the
  // emulator's (a frame acquired just before the stop may be counted there only).
  if (c.stall_every == 0) {
    EXPECT_LE(run.stats.frames_missed, frames / 100 + 1);
  }
  EXPECT_NEAR(static_cast<double>(run.stats.frames_missed), static_cast<double>(e.frames_missed),
              2.0);
}

INSTANTIATE_TEST_SUITE_P(
    RadarBehaviours, Lt102PacingTest,
    ::testing::Values(PacingCase{"latest_100", false, 10, 100},
                      PacingCase{"latest_50_of_100_asked", false, 20, 100},
                      PacingCase{"hold_100", true, 10, 100},
                      PacingCase{"latest_100_late_frames", false, 10, 100, 25}),
    [](const ::testing::TestParamInfo<PacingCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace uwbsar::live
