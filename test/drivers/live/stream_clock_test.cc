// The passive-synchronisation stamp filter (drivers/live/stream_clock.h) against synthetic
// arrivals: true send time + a non-negative random delay (an idle machine: transfer plus a
// little jitter; a loaded one: the reading thread delayed by up to tens of milliseconds),
// with gaps, a frame-rate change, a device clock restart and a reset.
#include "drivers/live/stream_clock.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace uwbsar::live {
namespace {

struct Errors {
  double p50_ms, p99_ms, max_ms;
};

Errors Summarise(std::vector<double> e_ms) {
  for (double& e : e_ms) e = std::abs(e);
  std::sort(e_ms.begin(), e_ms.end());
  auto at = [&](double p) {
    return e_ms[std::min(e_ms.size() - 1,
                         static_cast<std::size_t>(p * static_cast<double>(e_ms.size() - 1)))];
  };
  return {at(0.5), at(0.99), e_ms.back()};
}

/// Delay of one arrival: 0.3 ms transfer, exponential jitter, and under load a thread
/// that is not scheduled for up to `stall_ms` one time in `stall_one_in`.
struct DelayModel {
  double jitter_mean_ms = 0.2;
  double stall_ms = 0.0;
  int stall_one_in = 20;
  double Draw(std::mt19937_64& rng) const {
    double d = 0.3 + std::exponential_distribution<double>(1.0 / jitter_mean_ms)(rng);
    if (stall_ms > 0 && rng() % stall_one_in == 0) {
      d += std::uniform_real_distribution<double>(0, stall_ms)(rng);
    }
    return d;
  }
};

struct StreamRun {
  Errors raw, filtered;
  long long reanchors;
};

/// A 100 frames/s stream (period 10 ms, the device 50 ppm fast) of `n` frames, indexed
/// by frame number; returns the errors against the true send times after `settle` frames.
StreamRun Simulate(const DelayModel& delay, int n, int settle, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  StreamClockOptions options;
  options.nominal_ns_per_unit = 1e7;
  StreamClock clock(options);
  const double period_ns = 1e7 * (1.0 - 50e-6);
  const TimestampNs t0 = 1'700'000'000'000'000'000;
  std::vector<double> raw, filtered;
  TimestampNs last_stamp = 0, last_arrival = 0;
  for (int k = 0; k < n; ++k) {
    const TimestampNs truth = t0 + static_cast<TimestampNs>(std::llround(period_ns * k));
    // A serial line delivers in order: an arrival is never before the previous one.
    TimestampNs arrival = truth + static_cast<TimestampNs>(std::llround(delay.Draw(rng) * 1e6));
    arrival = std::max(arrival, last_arrival);
    last_arrival = arrival;
    const TimestampNs stamp = clock.Stamp(k, arrival);
    EXPECT_LE(stamp, arrival) << "frame " << k;
    if (k > 0) {
      EXPECT_GT(stamp, last_stamp) << "frame " << k;
    }
    last_stamp = stamp;
    if (k < settle) continue;
    raw.push_back(static_cast<double>(arrival - truth) * 1e-6);
    filtered.push_back(static_cast<double>(stamp - truth) * 1e-6);
  }
  return {Summarise(raw), Summarise(filtered), clock.reanchors()};
}

void Print(const char* what, const StreamRun& r) {
  std::printf(
      "%s: raw p50 %.3f p99 %.3f max %.3f ms; filtered p50 %.3f p99 %.3f max %.3f ms; "
      "re-anchors %lld\n",
      what, r.raw.p50_ms, r.raw.p99_ms, r.raw.max_ms, r.filtered.p50_ms, r.filtered.p99_ms,
      r.filtered.max_ms, r.reanchors);
}

TEST(StreamClockTest, IdleArrivalsAreStampedWithinTheTransferTime) {
  const StreamRun r = Simulate(DelayModel{}, 6000, 100, 1);
  Print("idle", r);
  // The envelope sits at the smallest delay (0.3 ms transfer): the filtered error is about
  // that, with no jitter on top.
  EXPECT_LT(r.filtered.p99_ms, 0.6);
  EXPECT_LT(r.filtered.max_ms, 0.8);
  EXPECT_GT(r.raw.p99_ms, r.filtered.p99_ms);
  EXPECT_EQ(r.reanchors, 0);
}

TEST(StreamClockTest, ArrivalsDelayedByALoadedSchedulerDoNotMoveTheStamps) {
  DelayModel loaded;
  loaded.jitter_mean_ms = 1.0;
  loaded.stall_ms = 40.0;  // one arrival in 20 held back by up to 40 ms
  const StreamRun r = Simulate(loaded, 6000, 100, 2);
  Print("loaded", r);
  EXPECT_GT(r.raw.p99_ms, 10.0);  // what stamping at arrival costs
  EXPECT_LT(r.filtered.p99_ms, 0.8);
  EXPECT_LT(r.filtered.max_ms, 1.0);
  EXPECT_EQ(r.reanchors, 0);
}

TEST(StreamClockTest, AGapReanchorsAndTheStampsRecover) {
  std::mt19937_64 rng(3);
  StreamClock clock;  // 10 ms nominal, gap_units 200
  const TimestampNs t0 = 1'000'000'000'000;
  DelayModel delay;
  double worst_after_ms = 0.0;
  for (int k = 0; k < 2000; ++k) {
    if (k >= 500 && k < 1500) continue;  // 10 s without frames (the cable out)
    // After the gap the device restarted with another phase: +3.7 ms.
    const TimestampNs truth = t0 + k * 10'000'000LL + (k >= 1500 ? 3'700'000 : 0);
    const TimestampNs arrival =
        truth + static_cast<TimestampNs>(std::llround(delay.Draw(rng) * 1e6));
    const TimestampNs stamp = clock.Stamp(k, arrival);
    if (k >= 1600)
      worst_after_ms =
          std::max(worst_after_ms, std::abs(static_cast<double>(stamp - truth) * 1e-6));
  }
  EXPECT_EQ(clock.reanchors(), 1);
  EXPECT_LT(worst_after_ms, 0.8);
}

TEST(StreamClockTest, AFrameRateChangeOnTheDeviceMillisecondCounterNeedsNoReanchor) {
  // The Kobuki's frames carry its millisecond counter: x is device time, so a change
  // from 50 to 20 packets/s only spaces x differently.
  std::mt19937_64 rng(4);
  StreamClockOptions options;
  options.nominal_ns_per_unit = 1e6;
  options.gap_units = 2000;
  StreamClock clock(options);
  DelayModel delay;
  delay.stall_ms = 20.0;
  std::int64_t ms = 0;
  double worst_ms = 0.0;
  for (int k = 0; k < 3000; ++k) {
    ms += k < 1500 ? 20 : 50;
    const TimestampNs truth = 5'000'000'000LL + ms * 1'000'000LL;
    const TimestampNs arrival =
        truth + static_cast<TimestampNs>(std::llround(delay.Draw(rng) * 1e6));
    const TimestampNs stamp = clock.Stamp(ms, arrival);
    if (k > 100) worst_ms = std::max(worst_ms, std::abs(static_cast<double>(stamp - truth) * 1e-6));
  }
  EXPECT_EQ(clock.reanchors(), 0);
  EXPECT_LT(worst_ms, 1.0);
}

TEST(StreamClockTest, ADeviceClockRestartOrResetReanchors) {
  StreamClock clock;
  TimestampNs t = 1'000'000'000;
  for (int k = 0; k < 100; ++k) clock.Stamp(1000 + k, t += 10'000'000);
  // The counter restarts (x goes back): a new anchor, and the stamp is the arrival.
  EXPECT_EQ(clock.Stamp(5, t + 10'000'000), t + 10'000'000);
  EXPECT_EQ(clock.reanchors(), 1);
  // A reset with a new nominal period (the radar restarted at 50 frames/s).
  clock.Reset(2e7);
  t += 1'000'000'000;
  for (int k = 0; k < 100; ++k) clock.Stamp(k, t + k * 20'000'000LL);
  EXPECT_EQ(clock.reanchors(), 2);
  EXPECT_NEAR(clock.ns_per_unit(), 2e7, 1e3);
  EXPECT_EQ(clock.Predict(100), t + 100 * 20'000'000LL);
}

TEST(StreamClockTest, ADeviceClockThatJumpsEarlierReanchors) {
  StreamClock clock;
  TimestampNs t = 1'000'000'000;
  for (int k = 0; k < 100; ++k) clock.Stamp(k, t + k * 10'000'000LL);
  // The device's counter jumps 5 frames ahead: the frame arrives 50 ms before the line
  // says it was sent.
  const TimestampNs arrival = t + 100 * 10'000'000LL;
  EXPECT_EQ(clock.Stamp(105, arrival), arrival);
  EXPECT_EQ(clock.reanchors(), 1);
}

}  // namespace
}  // namespace uwbsar::live
