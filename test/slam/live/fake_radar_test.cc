// A radar model added without touching slam/: the test registers "fake" through the factory
// (drivers/live/radar_driver_factory.h), a driver that emits synthetic scans, sets
// live.radar_model: fake and runs `uwbsar run`'s runner on the emulated Kobuki base. Its
// scans reach the recording and SLAM (imaged with the geometry its start-up reported), and
// its generic counts and its own arrive in the result and live.json. Were the serial source
// to build an LT102 itself, the fake would never be created and nothing here would hold.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "drivers/live/radar_driver_factory.h"
#include "live_test_util.h"
#include "slam/app_config.h"
#include "test/shared_data.h"

namespace uwbsar::live {
namespace {

constexpr int kFakeSamples = 700;       // not radars[].num_samples (1000): the start-up's count
constexpr double kFakeRangeMinM = 0.3;  // not radars[].range_offset_m (0)

/// What the fakes were created with, for the test to check.
struct FakeLog {
  std::mutex mutex;
  std::vector<RadarDeviceArgs> created;
};

/// Emits a synthetic scan every 10 ms while its gate is open, stamped by the host clock.
class FakeRadar : public RadarDevice {
 public:
  explicit FakeRadar(const RadarDeviceArgs& args) : args_(args) {}
  ~FakeRadar() override { Stop(); }
  void Start() override {
    if (!thread_.joinable()) thread_ = std::thread([this] { Loop(); });
  }
  void Stop() override {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  bool connected() const override { return true; }
  bool WaitConfigured(double /*timeout_s*/, RadarSetup* setup, std::string* error) override {
    error->clear();
    *setup = Setup();
    return true;
  }
  RadarStartupWait startup_wait() const override { return {1.0, "fake.startup_wait_s"}; }
  long long scans() const override { return scans_; }
  RadarStats stats() const override {
    RadarStats s;
    s.startups = 1;
    s.configured = true;
    s.setup = Setup();
    s.frames_delivered = scans_;
    s.frames_missed = 0;
    s.extra = {{"fake_gated_polls", gated_.load()},
               {"fake_label", std::string("synthetic")},
               {"fake_timing_ms.period", 10.0}};
    return s;
  }

 private:
  static RadarSetup Setup() {
    RadarSetup setup;
    setup.range_min_m = kFakeRangeMinM;
    setup.range_max_m = 5.0;
    setup.samples_per_scan = kFakeSamples;
    setup.frame_rate_fps = 100;
    setup.frame_rate_requested_fps = 100;
    setup.description = "fake radar, synthetic scans";
    return setup;
  }
  void Loop() {
    long long frame = 0;
    while (!stop_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      if (args_.acquisition_gate && !args_.acquisition_gate()) {
        ++gated_;
        continue;
      }
      RadarScan scan;
      scan.sensor_id = args_.sensor_id;
      scan.stamp_ns = args_.clock ? args_.clock() : 0;
      scan.samples.resize(kFakeSamples);
      for (int k = 0; k < kFakeSamples; ++k) {
        scan.samples[k] =
            0.01f * static_cast<float>(std::sin(0.37 * k + 0.05 * static_cast<double>(frame)));
      }
      ++frame;
      args_.sink(std::move(scan));
      ++scans_;
    }
  }

  RadarDeviceArgs args_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<long long> scans_{0}, gated_{0};
};

TEST(FakeRadarTest, ARadarModelRegisteredThroughTheFactoryFeedsTheLiveRun) {
  UWBSAR_NEED_SEED_LAB_MAP();
  static FakeLog fake_log;
  RegisterRadarModel("fake", [](const RadarDeviceArgs& args) {
    std::lock_guard<std::mutex> lock(fake_log.mutex);
    fake_log.created.push_back(args);
    return std::make_unique<FakeRadar>(args);
  });
  Config config;
  config.live.radar_model = "fake";
  const EmulatedRun live = RunEmulated(config, "fake_radar", 2.0, 4.0);
  const slam::LiveRunResult& r = live.result;

  // Created through the factory, one per radars[] entry, with its device and name.
  {
    std::lock_guard<std::mutex> lock(fake_log.mutex);
    ASSERT_EQ(fake_log.created.size(), 2u);
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(fake_log.created[i].sensor_id, i);
      EXPECT_EQ(fake_log.created[i].name, "radar " + config.radars[i].name);
      EXPECT_EQ(fake_log.created[i].device, live.out_dir + "/dev/radar" + std::to_string(i));
    }
  }
  // Its scans arrived: counted, recorded, and imaged with the geometry its start-up reported.
  ASSERT_EQ(r.radars.size(), 2u);
  long long delivered = 0;
  for (const auto& [name, s] : r.radars) {
    EXPECT_GT(s.frames_delivered, 20) << name;
    EXPECT_EQ(s.setup.samples_per_scan, kFakeSamples);
    EXPECT_EQ(RadarCount<std::string>(s, "fake_label"), "synthetic");
    EXPECT_EQ(s.Extra("frame_requests"), nullptr);  // no LT102 counts
    delivered += s.frames_delivered;
  }
  EXPECT_EQ(r.scans_received, delivered);
  EXPECT_GE(r.recorded_messages, r.scans_received + r.odometry_received);
  EXPECT_GT(r.odometry_received, 0);
  ASSERT_TRUE(r.run.slam);
  for (const RadarConfig& radar : r.run.slam->config().radars) {
    EXPECT_EQ(radar.num_samples, kFakeSamples);
    EXPECT_EQ(radar.range_offset_m, kFakeRangeMinM);
  }
  const auto stats = r.run.slam->frontend_stats();
  EXPECT_EQ(stats.scans_rejected_length, 0);
  EXPECT_EQ(stats.scans_rejected_no_odometry, 0);  // the gate held them until odometry flowed
  EXPECT_GT(stats.scans_imaged, 0);

  // live.json: the generic keys, then the fake's own, nested where named "group.key".
  std::ifstream in(live.out_dir + "/live.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const std::string left = "radar " + config.radars[0].name;
  ASSERT_TRUE(j["radars"].contains(left));
  const nlohmann::json& jr = j["radars"][left];
  EXPECT_EQ(jr["frames_delivered"].get<long long>(), r.radars[0].second.frames_delivered);
  EXPECT_EQ(jr["frames_repeated"].get<long long>(), 0);
  EXPECT_EQ(jr["samples_per_scan"].get<int>(), kFakeSamples);
  EXPECT_EQ(jr["setup"].get<std::string>(), "fake radar, synthetic scans");
  EXPECT_EQ(jr["fake_label"].get<std::string>(), "synthetic");
  EXPECT_EQ(jr["fake_timing_ms"]["period"].get<double>(), 10.0);
  EXPECT_TRUE(jr["fake_gated_polls"].is_number_integer());
  EXPECT_FALSE(jr.contains("frame_requests"));
}

}  // namespace
}  // namespace uwbsar::live
