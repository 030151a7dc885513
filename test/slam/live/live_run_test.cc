// The live runner on a shortened emulated run: what it records, maps offline to the
// same trajectory it produced live; it measures latency and writes its outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "live_test_util.h"
#include "slam/app_config.h"
#include "test/shared_data.h"

namespace uwbsar::live {
namespace {

TEST(LiveRunTest, RecordingMappedOfflineReproducesTheLiveTrajectory) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config;
  config.live.snapshot_period_s = 1.0;
  const EmulatedRun live = RunEmulated(config, "short", 2.0, 14.0);
  const slam::LiveRunResult& r = live.result;
  ASSERT_TRUE(r.run.slam);
  ASSERT_FALSE(r.run.slam->keyframes().empty());
  EXPECT_EQ(r.dropped_from_processing, 0);
  // Data flowed (not a rate check): about 2700 scans idle, 1290 under uwbsar_load, where the
  // emulator's starved thread acquires frames back to back and overwrites some (1952 under
  // ASan). Every frame the emulator answered must have arrived (one per radar may be in
  // flight at the stop).
  EXPECT_GE(r.scans_received, live.emulator.scans_sent - live.emulator.frames_repeated - 2);
  EXPECT_GT(r.scans_received, 500);
  // Every scan and odometry sample is recorded (plus GPIO / fault / run events).
  EXPECT_GE(r.recorded_messages, r.scans_received + r.odometry_received);
  EXPECT_GT(r.latency_samples, 500);
  EXPECT_GT(r.latency_p99_ms, 0.0);
  // Snapshots were taken while SLAM ran (not a rate check: each waits for the first
  // keyframe and takes about 0.1 s idle, up to 2 s with uwbsar_load and a compiler busy, when
  // a 2 s period gave one snapshot in the 7 s run).
  EXPECT_GE(r.snapshots, 1);
  // Offline, from the recording: the same trajectory, pose by pose.
  const slam::MapRun offline = slam::MapBag(config, r.recording_path, false);
  const auto a = r.run.slam->CorrectedTrajectory();
  const auto b = offline.slam->CorrectedTrajectory();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].first, b[k].first);
    ASSERT_NEAR(a[k].second.x_m, b[k].second.x_m, 1e-6);
    ASSERT_NEAR(a[k].second.y_m, b[k].second.y_m, 1e-6);
  }
  EXPECT_EQ(offline.slam->keyframes().size(), r.run.slam->keyframes().size());
  // live.json holds the figures.
  std::ifstream in(live.out_dir + "/live.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["scan_latency_ms"]["samples"].get<long long>(), r.latency_samples);
  EXPECT_TRUE(std::filesystem::exists(live.out_dir + "/summary.json"));
  // ATE against the emulator's ground truth is measured (same clock as the drivers).
  EXPECT_GT(r.outputs.ate.num_poses, 100);
  EXPECT_LT(r.outputs.ate.rmse_m, 0.05);
}

TEST(LiveRunTest, DeviceListNotMatchingTheRadarsIsAnInputError) {
  Config config;
  config.live.radar_devices = {"/dev/ttyACM0"};
  slam::LiveRunOptions options;
  options.out_dir = std::filesystem::temp_directory_path() / "uwbsar_live_bad";
  EXPECT_THROW(slam::RunLive(config, std::move(options)), InputError);
}

long long Fault(const slam::LiveRunResult& r, const std::string& kind) {
  auto it = r.faults.find(kind);
  return it == r.faults.end() ? 0 : it->second;
}

TEST(LiveRunTest, TheEchoedRangeNotTheYamlSetsTheImagingGeometry) {
  Config config;  // radars[]: sample 0 at 0 m, 1000 samples
  config.live.lt102.range_min_m = 0.5;
  config.live.lt102.range_max_m = 3.0;
  const EmulatedRun live = RunEmulated(config, "range", 2.0, 8.0);
  const slam::LiveRunResult& r = live.result;
  const double bin_m = 299792458.0 / (2 * 23.328e9);
  for (const RadarConfig& radar : r.run.slam->config().radars) {
    EXPECT_NEAR(radar.range_offset_m, 78 * bin_m, 1e-6);  // 0.5 m on the radar's grid
    EXPECT_EQ(radar.num_samples, 390);
  }
  const FrontendStats s = r.run.slam->frontend_stats();
  std::printf("range 0.5-3.0 m: %lld scans imaged, %lld rejected for their length; ATE %.2f cm\n",
              s.scans_imaged, s.scans_rejected_length, 100 * r.outputs.ate.rmse_m);
  EXPECT_EQ(s.scans_rejected_length, 0);
  EXPECT_GT(s.scans_imaged, 100);
  EXPECT_LT(r.outputs.ate.rmse_m, 0.05);
}

TEST(LiveRunTest, Lt102FaultsAreCountedAndEveryScanThatArrivedIsRecorded) {
  Config config;
  EmulatorFaults faults;
  faults.lt102_crc = true;  // detected from the version answer (live.lt102.crc: auto)
  faults.lt102_bad_size_every = 50;
  faults.lt102_missing_answer_code = 'd';
  faults.lt102_missing_answer_times = 3;     // 0.75 s without bytes: under live.read_timeout_s
  config.live.lt102.frame_timeout_s = 0.25;  // the request in flight when the run ends stays so
  const EmulatedRun live = RunEmulated(config, "lt102_faults", 2.0, 8.0, faults);
  const slam::LiveRunResult& r = live.result;
  long long answers = 0, invalid = 0, repeated = 0;
  for (const auto& [name, s] : r.radars) {
    std::printf("%s: %lld requests, %lld answers, %lld lost, %lld invalid; CRC %s\n", name.c_str(),
                RadarCount(s, "frame_requests"), RadarCount(s, "frame_answers"), s.frames_lost,
                s.invalid_frames, Lt102Crc(s) ? "on" : "off");
    EXPECT_TRUE(Lt102Crc(s));
    EXPECT_EQ(s.frames_lost, 3);
    EXPECT_EQ(s.startups, 1);
    EXPECT_GT(s.invalid_frames, 0);
    answers += RadarCount(s, "frame_answers") + RadarCount(s, "late_answers");
    invalid += s.invalid_frames;
    repeated += s.frames_repeated;
  }
  EXPECT_EQ(Fault(r, "radar left: lost frames"), 3);
  EXPECT_GT(Fault(r, "radar right: invalid raw-data messages"), 0);
  EXPECT_EQ(r.scans_received, answers - invalid - repeated);
  EXPECT_GE(r.recorded_messages, r.scans_received + r.odometry_received);
  ASSERT_FALSE(r.run.slam->keyframes().empty());
}

TEST(LiveRunTest, ARadarRefusingASettingStopsTheRunWithOneLineNamingIt) {
  namespace fs = std::filesystem;
  Config config;
  const std::string dir =
      (fs::temp_directory_path() / ("uwbsar_live_refuse_" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  fs::create_directories(dir + "/dev");
  config.live.radar_devices = {dir + "/dev/radar0", dir + "/dev/radar1"};
  config.live.kobuki_device = dir + "/dev/kobuki";
  EmulatorFaults faults;
  faults.lt102_wrong_echo_code = lt102::kFormat;
  const sim::SimScenario scenario = sim::MakeScenario(config, SeedLabMapPath(), "depart-return", 1);
  HostClock clock;
  SimDevicePlayer player(
      config, scenario, 1, config.live.radar_devices, config.live.kobuki_device, 1.0, faults,
      [&] { return clock.Now(); }, 5.0);
  player.Start();
  slam::LiveRunOptions options;
  options.out_dir = dir;
  options.quiet = true;
  std::atomic<bool> stop{true};
  options.stop = &stop;
  try {
    slam::RunLive(config, std::move(options));
    ADD_FAILURE() << "the run started";
  } catch (const InputError& e) {
    std::printf("refused: %s\n", e.what());
    EXPECT_EQ(std::string(e.what()),
              "radar left: configuration error: sample format (0x0A) sent 1, the radar echoed 2");
  }
  player.Stop();
  EXPECT_FALSE(fs::exists(dir + "/live.json"));
}

struct PollCase {
  const char* name;
  int radar_fps;  ///< the emulated radars' actual frame rate (the simulated scan rate)
  bool crc;
};

void PrintTo(const PollCase& c, std::ostream* os) { *os << c.name; }

class LivePollingTest : public ::testing::TestWithParam<PollCase> {};

// Against radars that answer `d` at once with their latest frame (the vendor behaviour),
// from two radars on the 2-core machine: polls within 10 % of the radar's frame rate (the
// rate it answers to `f`, here also when 100 was asked and it runs at 50), no frame delivered
// twice (repeats dropped, counted as the emulator counted them), misses at most 1 % (3 %
// under uwbsar_load: UWBSAR_UNDER_LOAD), counted as the emulator counted them; live.json holds
// the figures.
TEST_P(LivePollingTest, EachFrameOnceAtTheRadarsFrameRate) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const PollCase c = GetParam();
  Config config;
  config.simulator.radar.rate_hz = c.radar_fps;
  config.live.lt102.frame_timeout_s = 0.5;  // the request in flight when the run ends stays so
  EmulatorFaults faults;
  faults.lt102_crc = c.crc;
  faults.lt102_actual_frame_rate_fps = c.radar_fps;
  const EmulatedRun live = RunEmulated(config, std::string("poll_") + c.name, 1.0, 10.0, faults, 1,
                                       {}, /*asked_frame_rate_fps=*/100);
  const slam::LiveRunResult& r = live.result;
  ASSERT_EQ(r.radars.size(), 2u);
  const bool loaded = std::getenv("UWBSAR_UNDER_LOAD") != nullptr;
  long long delivered = 0, repeated = 0, missed = 0;
  std::ifstream in(live.out_dir + "/live.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const auto& [name, s] : r.radars) {
    const double polls_per_s = RadarCount<double>(s, "requests_per_s");
    std::printf(
        "%s%s, %s at %d frames/s (%d asked), CRC %s: %lld requests (%.1f/s), %lld answers, "
        "%lld frames, %lld repeated, %lld missed, %lld lost; request-to-answer p50 %.2f ms, p99 "
        "%.2f ms\n",
        c.name, loaded ? " (under load)" : "", name.c_str(), s.setup.frame_rate_fps,
        s.setup.frame_rate_requested_fps, Lt102Crc(s) ? "on" : "off",
        RadarCount(s, "frame_requests"), polls_per_s, RadarCount(s, "frame_answers"),
        s.frames_delivered, s.frames_repeated, s.frames_missed, s.frames_lost,
        RadarCount<double>(s, "request_to_answer_ms.p50"),
        RadarCount<double>(s, "request_to_answer_ms.p99"));
    EXPECT_EQ(s.setup.frame_rate_fps, c.radar_fps);
    EXPECT_EQ(s.setup.frame_rate_requested_fps, 100);
    EXPECT_EQ(Lt102Crc(s), c.crc);
    EXPECT_EQ(s.frames_lost, 0);
    EXPECT_EQ(RadarCount(s, "frame_requests"),
              RadarCount(s, "frame_answers") + RadarCount(s, "unanswered_at_stop"));
    // The radar's frame rate, not faster: a late wake-up on a busy machine re-polls a frame not
    // yet replaced (113 polls/s at 100 frames/s while a build ran), counted as repeated and
    // never recorded twice (frames_repeated is checked against live.json below).
    EXPECT_GE(polls_per_s, 0.9 * c.radar_fps);
    EXPECT_LE(polls_per_s, 1.2 * c.radar_fps);
    EXPECT_LE(static_cast<double>(s.frames_missed),
              (loaded ? 0.03 : 0.01) * static_cast<double>(s.frames_delivered) + 1);
    const nlohmann::json& jr = j["radars"][name];
    EXPECT_EQ(jr["frames_repeated"].get<long long>(), s.frames_repeated);
    EXPECT_EQ(jr["frames_missed"].get<long long>(), s.frames_missed);
    EXPECT_EQ(jr["frames_delivered"].get<long long>(), s.frames_delivered);
    EXPECT_EQ(jr["frame_requests"].get<long long>(), RadarCount(s, "frame_requests"));
    EXPECT_EQ(jr["request_to_answer_ms"]["p99"].get<double>(),
              RadarCount<double>(s, "request_to_answer_ms.p99"));
    // An LT102's keys in live.json, as before the radar seam (generic counts + its own).
    std::set<std::string> keys;
    for (const auto& item : jr.items()) keys.insert(item.key());
    EXPECT_EQ(keys, (std::set<std::string>{"startups",
                                           "startup_failures",
                                           "config_errors",
                                           "frame_rate_fps",
                                           "frame_rate_requested_fps",
                                           "frame_requests",
                                           "frame_answers",
                                           "requests_per_s",
                                           "frames_delivered",
                                           "frames_repeated",
                                           "frames_missed",
                                           "frames_lost",
                                           "late_answers",
                                           "stamp_reanchors",
                                           "unanswered_at_stop",
                                           "invalid_frames",
                                           "request_to_answer_ms",
                                           "command_requests",
                                           "wrong_answers",
                                           "missing_answers",
                                           "retries",
                                           "stops_sent",
                                           "configured",
                                           "setup",
                                           "range_min_m",
                                           "range_max_m",
                                           "samples_per_scan"}));
    EXPECT_EQ(jr["request_to_answer_ms"].size(), 3u);
    delivered += s.frames_delivered;
    repeated += s.frames_repeated;
    missed += s.frames_missed;
  }
  const EmulatorCounts& e = live.emulator;
  std::printf(
      "%s%s emulator: %lld frames acquired, %lld answered, %lld repeated, %lld missed, %lld "
      "overwritten before a request\n",
      c.name, loaded ? " (under load)" : "", e.frames_acquired, e.scans_sent, e.frames_repeated,
      e.frames_missed, e.frames_overwritten);
  // Every scan is a distinct frame: the answers less the repeats the emulator counted.
  EXPECT_EQ(repeated, e.frames_repeated);
  EXPECT_EQ(delivered, e.scans_sent - e.frames_repeated);
  EXPECT_EQ(r.scans_received, delivered);
  // Misses as the emulator counted them (a frame acquired just before a radar's stop is
  // counted there only).
  EXPECT_NEAR(static_cast<double>(missed), static_cast<double>(e.frames_missed), 2.0);
}

// Named under LiveRunTest so that CI runs it again under uwbsar_load with the other live tests.
INSTANTIATE_TEST_SUITE_P(
    LiveRunTest, LivePollingTest,
    ::testing::Values(PollCase{"fps100", 100, false}, PollCase{"fps100_crc", 100, true},
                      PollCase{"fps50", 50, false}, PollCase{"fps50_crc", 50, true}),
    [](const ::testing::TestParamInfo<PollCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace uwbsar::live

namespace uwbsar::live {
namespace {

struct ErrorStats {
  double p50_ms = 0, p99_ms = 0, max_ms = 0;
};
ErrorStats Stats(std::vector<double> v) {
  for (double& e : v) e = std::abs(e);
  std::sort(v.begin(), v.end());
  if (v.empty()) return {};
  auto at = [&](double p) {
    return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
  };
  return {at(0.5), at(0.99), v.back()};
}

// A radar scan's stamp is its acquisition time on the emulator (taken on
// the same host clock), not its arrival: the filtered error is printed next to the raw
// arrival's (docs/live.md table), idle and, in .ci/run, under uwbsar_load.
TEST(LiveRunTest, RadarStampsFollowTheAcquisitionTimesNotTheArrivals) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config;
  const EmulatedRun live = RunEmulated(config, "stamps", 1.0, 12.0);
  ASSERT_EQ(live.result.radars.size(), live.scan_send_ns.size());
  std::vector<double> raw, filtered;
  for (std::size_t r = 0; r < live.scan_send_ns.size(); ++r) {
    const std::vector<TimestampNs>& truth = live.scan_send_ns[r];
    const auto& trace = live.result.radars[r].second.stamp_trace;
    ASSERT_GT(trace.size(), 500u);
    for (std::size_t i = 100; i < trace.size(); ++i) {  // after the envelope settled
      const auto [arrival, stamp] = trace[i];
      // The frame is the acquisition nearest its stamp.
      auto it = std::lower_bound(truth.begin(), truth.end(), stamp);
      if (it == truth.end() || (it != truth.begin() && stamp - *(it - 1) < *it - stamp)) --it;
      raw.push_back(static_cast<double>(arrival - *it) * 1e-6);
      filtered.push_back(static_cast<double>(stamp - *it) * 1e-6);
    }
  }
  const ErrorStats a = Stats(raw), f = Stats(filtered);
  std::printf(
      "stamps%s: %zu scans; raw arrival error p50 %.3f p99 %.3f max %.3f ms; filtered p50 "
      "%.3f p99 %.3f max %.3f ms\n",
      std::getenv("UWBSAR_UNDER_LOAD") ? " (under load)" : "", raw.size(), a.p50_ms, a.p99_ms,
      a.max_ms, f.p50_ms, f.p99_ms, f.max_ms);
  // Relative, not absolute (a frame more than half a period off is matched to its
  // neighbour, so 5 ms is the measure's ceiling). A constant
  // delay (the transfer, or the emulator writing a frame slowly under ASan) is in the raw
  // arrivals and in the lower envelope alike. Measured raw vs filtered p50 / p99:
  // - normal priority, idle: 0.67 / 3.1 vs 0.43 / 0.70 ms; under uwbsar_load 6.4 / 40 vs
  //   1.8 / 4.9 ms;
  // - SCHED_FIFO (live.driver_priority) with compilers and uwbsar_load: 0.60 / 8.9-23 vs
  //   0.50 / 4.4-4.8 ms; under uwbsar_load alone 0.49 / 0.69 vs 0.42 / 0.52 ms;
  // - under ASan: 2.23 / 2.58 vs 2.54 / 2.60 ms (a 2.2 ms constant delay in both).
  // - clean arrivals at SCHED_FIFO, idle: once 0.50 / 0.97 vs 0.30 / 1.20 ms (the envelope's
  //   own error, about 1 ms, then shows in the tail).
  // - idle, once: 0.75 / 4.66 vs 1.89 / 4.47 ms (the filtered median 1.1 ms above the raw
  //   one: not yet understood, so the medians are reported, not compared).
  // So the filtered tail is held to the arrivals' tail or 1.5 ms, whichever is larger, with
  // 0.5 ms of margin: a filter that lost the frame grid is off by up to half a period.
  EXPECT_LT(f.p99_ms, std::max(a.p99_ms, 1.5) + 0.5);
}

}  // namespace
}  // namespace uwbsar::live
