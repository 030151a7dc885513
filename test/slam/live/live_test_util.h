// Runs `RunLive` in-process against emulated devices (pty LT102 x2 + Kobuki) that play
// the simulated seed_lab run; shared by the live runner tests.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <variant>

#include "drivers/emulators/sim_device_player.h"
#include "drivers/live/host_clock.h"
#include "drivers/live/radar_device.h"
#include "slam/app_config.h"
#include "slam/live/live_runner.h"
#include "test/shared_data.h"

namespace uwbsar::live {

struct EmulatedRun {
  slam::LiveRunResult result;
  std::vector<OdometrySample> ground_truth;
  EmulatorCounts emulator;
  std::string out_dir;
  std::vector<std::vector<TimestampNs>> scan_send_ns;  ///< per radar, true acquisition times
};

/// The accepted loops as (earlier keyframe, new keyframe) ids: keyframe ids are world-
/// lattice segment numbers, so two runs over the same path number them alike.
inline std::set<std::pair<int, int>> AcceptedPairs(const slam::SlamSystem& slam) {
  std::set<std::pair<int, int>> pairs;
  for (const slam::LoopRecord& l : slam.loops()) {
    if (l.accepted()) pairs.insert({l.match_id, l.query_id});
  }
  return pairs;
}

/// A radar's own counter `name` (for the LT102: Lt102Radar::ToRadarStats); a failure when
/// the radar has none of that type.
template <class T = long long>
T RadarCount(const RadarStats& s, const std::string& name) {
  const RadarStatValue* value = s.Extra(name);
  EXPECT_TRUE(value != nullptr && std::holds_alternative<T>(*value)) << name;
  return value != nullptr && std::holds_alternative<T>(*value) ? std::get<T>(*value) : T{};
}

/// An LT102's start-up found the CRC byte on (its setup line says so).
inline bool Lt102Crc(const RadarStats& s) {
  return s.setup.description.find("; CRC on;") != std::string::npos;
}

inline std::string SeedLabMapPath() { return ::uwbsar::testing::SeedLabLidarMap(); }

/// `seed`: the simulation seed of the played run (the scene is always seed 1's);
/// `localize_in`: LiveRunOptions::localize_in; `asked_frame_rate_fps` > 0: the frame rate
/// the drivers ask for instead of the emulated radars' (which answer theirs).
inline EmulatedRun RunEmulated(Config config, const std::string& name, double speed,
                               double duration_s, const EmulatorFaults& faults = {},
                               std::uint64_t seed = 1, const std::string& localize_in = {},
                               int asked_frame_rate_fps = 0) {
  namespace fs = std::filesystem;
  EmulatedRun out;
  out.out_dir =
      (fs::temp_directory_path() / ("uwbsar_live_" + name + "_" + std::to_string(::getpid())))
          .string();
  fs::remove_all(out.out_dir);
  fs::create_directories(out.out_dir + "/dev");
  config.live.radar_devices = {out.out_dir + "/dev/radar0", out.out_dir + "/dev/radar1"};
  config.live.kobuki_device = out.out_dir + "/dev/kobuki";
  ConfigureLiveForEmulation(config.simulator, speed, &config.live);
  if (asked_frame_rate_fps > 0) config.live.lt102.frame_rate_fps = asked_frame_rate_fps;
  config.live.lt102.sample_format = 3;  // F32: the simulated samples unquantised
  const sim::SimScenario scenario = sim::MakeScenario(config, SeedLabMapPath(), "depart-return", 1);
  HostClock truth_clock(speed);
  SimDevicePlayer player(
      config, scenario, seed, config.live.radar_devices, config.live.kobuki_device, speed, faults,
      [&] { return truth_clock.Now(); }, duration_s);
  std::atomic<bool> stop{false};
  slam::LiveRunOptions options;
  options.out_dir = out.out_dir;
  options.recording_dir = out.out_dir + "/recording";
  options.time_scale = speed;
  options.stop = &stop;
  options.quiet = true;
  options.ground_truth = [&] { return player.ground_truth(); };
  options.localize_in = localize_in;
  player.Start();
  std::thread watcher([&] {
    while (!player.done()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    stop = true;
  });
  out.result = slam::RunLive(config, std::move(options));
  watcher.join();
  player.Stop();
  out.ground_truth = player.ground_truth();
  out.emulator = player.counts();
  out.scan_send_ns = player.scan_send_ns();
  return out;
}

}  // namespace uwbsar::live
