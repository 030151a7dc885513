// The radar seam: the registry behind live.radar_model (the LT102 seeded, a model registered
// at run time, an unknown model refused naming the known ones) and the LT102 created through
// it against the emulated module, its counts as the generic RadarStats.
#include "drivers/live/radar_driver_factory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <string>
#include <variant>

#include "core/config_io.h"
#include "drivers/live/live_config.h"
#include "drivers/live/lt102_radar.h"
#include "lt102_test_util.h"
#include "slam/app_config.h"

namespace uwbsar::live {
namespace {

/// A radar that does nothing: records what it was created with.
class IdleRadar : public RadarDevice {
 public:
  explicit IdleRadar(const RadarDeviceArgs& args) : args_(args) {}
  void Start() override {}
  void Stop() override {}
  bool connected() const override { return true; }
  bool WaitConfigured(double, RadarSetup*, std::string*) override { return false; }
  RadarStartupWait startup_wait() const override { return {0.0, "test.wait_s"}; }
  long long scans() const override { return 0; }
  RadarStats stats() const override { return {}; }
  const RadarDeviceArgs& args() const { return args_; }

 private:
  RadarDeviceArgs args_;
};

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(RadarDriverFactoryTest, TheLt102IsRegisteredAndTheDefaultModel) {
  const std::vector<std::string> models = RadarModels();
  EXPECT_NE(std::find(models.begin(), models.end(), "lt102"), models.end());
  EXPECT_EQ(LiveConfig{}.radar_model, "lt102");
  EXPECT_TRUE(IsRadarModel("lt102"));
  EXPECT_NO_THROW(Validate(LiveConfig{}, "x.yaml"));
}

TEST(RadarDriverFactoryTest, AnUnknownModelIsRefusedNamingTheKeyAndTheKnownModels) {
  LiveConfig config;
  config.radar_model = "lt103";
  const std::string validate = ErrorOf([&] { Validate(config, "robot.yaml"); });
  EXPECT_NE(validate.find("robot.yaml: 'live.radar_model' is 'lt103', not a known radar model ("),
            std::string::npos)
      << validate;
  EXPECT_NE(validate.find("lt102"), std::string::npos) << validate;
  const std::string create = ErrorOf([] { CreateRadar("lt103", RadarDeviceArgs{}); });
  EXPECT_NE(create.find("'live.radar_model' is 'lt103'"), std::string::npos) << create;
  EXPECT_NE(create.find("lt102"), std::string::npos) << create;
  EXPECT_NE(ErrorOf([] { RequireRadarModel("lt103"); }), "");
  EXPECT_EQ(ErrorOf([] { RequireRadarModel("lt102"); }), "");
}

TEST(RadarDriverFactoryTest, ARegisteredModelIsValidAndCreatedWithItsArguments) {
  std::atomic<int> created{0};
  RegisterRadarModel("idle_test", [&](const RadarDeviceArgs& args) {
    ++created;
    return std::make_unique<IdleRadar>(args);
  });
  EXPECT_TRUE(IsRadarModel("idle_test"));
  LiveConfig config;
  config.radar_model = "idle_test";
  EXPECT_NO_THROW(Validate(config, "x.yaml"));
  RadarDeviceArgs args;
  args.name = "radar right";
  args.sensor_id = 1;
  args.device = "/dev/idle1";
  const std::unique_ptr<RadarDevice> radar = CreateRadar("idle_test", args);
  EXPECT_EQ(created, 1);
  const auto* idle = dynamic_cast<const IdleRadar*>(radar.get());
  ASSERT_NE(idle, nullptr);
  EXPECT_EQ(idle->args().name, "radar right");
  EXPECT_EQ(idle->args().sensor_id, 1);
  EXPECT_EQ(idle->args().device, "/dev/idle1");
  // The known models now name it too.
  const std::string error = ErrorOf([] { CreateRadar("lt103", RadarDeviceArgs{}); });
  EXPECT_NE(error.find("idle_test"), std::string::npos) << error;
}

TEST(RadarDriverFactoryTest, Lt102CountsBecomeTheGenericStatsAndItsOwn) {
  Lt102Stats s;
  s.startups = 2;
  s.requests = 100;
  s.answers = 98;
  s.frames_delivered = 90;
  s.frames_repeated = 8;
  s.frames_missed = 3;
  s.lost = 2;
  s.invalid_frames = 1;
  s.acquiring_s = 4.0;
  s.answer_p99_ms = 7.5;
  s.configured = true;
  s.setup.range_min_m = 0.5;
  s.setup.samples_per_scan = 321;
  s.setup.frame_rate_fps = 25;
  const RadarStats g = Lt102Radar::ToRadarStats(s);
  EXPECT_EQ(g.startups, 2);
  EXPECT_EQ(g.frames_delivered, 90);
  EXPECT_EQ(g.frames_repeated, 8);
  EXPECT_EQ(g.frames_missed, 3);
  EXPECT_EQ(g.frames_lost, 2);
  EXPECT_EQ(g.invalid_frames, 1);
  EXPECT_TRUE(g.configured);
  EXPECT_EQ(g.setup.range_min_m, 0.5);
  EXPECT_EQ(g.setup.samples_per_scan, 321);
  EXPECT_EQ(g.setup.frame_rate_fps, 25);
  EXPECT_EQ(g.setup.description, s.setup.Describe());
  ASSERT_NE(g.Extra("frame_requests"), nullptr);
  EXPECT_EQ(std::get<long long>(*g.Extra("frame_requests")), 100);
  EXPECT_EQ(std::get<long long>(*g.Extra("frame_answers")), 98);
  EXPECT_EQ(std::get<double>(*g.Extra("requests_per_s")), 25.0);
  EXPECT_EQ(std::get<double>(*g.Extra("request_to_answer_ms.p99")), 7.5);
  EXPECT_EQ(g.Extra("no_such_counter"), nullptr);
}

// The LT102 as the live source creates it: through the factory, against the emulated module.
TEST(RadarDriverFactoryTest, TheLt102CreatedByModelStartsAcquiresAndStops) {
  EmulatedLt102 emulated("factory");
  Config config;
  FaultLog faults;
  std::mutex mutex;
  long long delivered = 0;
  RadarDeviceArgs args;
  args.name = "radar left";
  args.device = emulated.path();
  args.link.reconnect_initial_s = 0.01;
  args.settings = config;
  args.faults = &faults;
  args.sink = [&](RadarScan&&) {
    std::lock_guard<std::mutex> lock(mutex);
    ++delivered;
  };
  std::atomic<bool> gate{false};
  args.acquisition_gate = [&] { return gate.load(); };
  const std::unique_ptr<RadarDevice> radar = CreateRadar("lt102", args);
  ASSERT_NE(dynamic_cast<Lt102Radar*>(radar.get()), nullptr);
  EXPECT_EQ(radar->startup_wait().key, "live.lt102.startup_wait_s");
  EXPECT_EQ(radar->startup_wait().wait_s, config.live.lt102.startup_wait_s);
  radar->Start();
  RadarSetup setup;
  std::string error;
  ASSERT_TRUE(radar->WaitConfigured(5.0, &setup, &error)) << error;
  EXPECT_GT(setup.samples_per_scan, 0);
  EXPECT_EQ(setup.frame_rate_requested_fps, config.live.lt102.frame_rate_fps);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(radar->scans(), 0);  // the gate is closed: nothing polled
  gate = true;
  EXPECT_TRUE(WaitUntil([&] { return radar->scans() >= 20; }));
  EXPECT_TRUE(radar->connected());
  radar->RequestStop();
  radar->Stop();
  const RadarStats stats = radar->stats();
  EXPECT_EQ(stats.frames_delivered, radar->scans());
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_EQ(delivered, stats.frames_delivered);
  EXPECT_EQ(stats.startups, 1);
  EXPECT_TRUE(stats.configured);
  EXPECT_EQ(stats.setup.samples_per_scan, setup.samples_per_scan);
  ASSERT_NE(stats.Extra("stops_sent"), nullptr);
  EXPECT_EQ(std::get<long long>(*stats.Extra("stops_sent")), 1);
  EXPECT_GE(std::get<long long>(*stats.Extra("frame_requests")), stats.frames_delivered);
}

}  // namespace
}  // namespace uwbsar::live
