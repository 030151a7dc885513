#include "slam/live/live_emulation.h"

#include <chrono>
#include <filesystem>

#include "drivers/emulators/sim_device_player.h"
#include "drivers/live/host_clock.h"
#include "drivers/sim/sim_stream.h"
#include "slam/outputs/output_folder.h"

namespace uwbsar::slam {

LiveEmulation::LiveEmulation(const EmulationOptions& emulation, Config* config,
                             LiveRunOptions* options, std::atomic<bool>* stop)
    : stop_(stop) {
  EnsureDirectory(options->out_dir);
  dev_dir_ = (std::filesystem::path(options->out_dir) / "dev").string();
  std::error_code ec;
  created_dev_dir_ = !std::filesystem::exists(dev_dir_, ec) && !ec;
  EnsureDirectory(dev_dir_);
  const std::string& dev_dir = dev_dir_;
  config->live.radar_devices.clear();
  for (std::size_t i = 0; i < config->radars.size(); ++i) {
    config->live.radar_devices.push_back(dev_dir + "/radar" + std::to_string(i));
  }
  config->live.kobuki_device = dev_dir + "/kobuki";
  config->live.gpio_chip.clear();
  config->live.radar_power_lines.clear();
  config->live.radar_reset_lines.clear();
  config->live.status_led_line = -1;
  options->time_scale = emulation.speed;
  live::ConfigureLiveForEmulation(config->simulator, emulation.speed, &config->live);
  const sim::SimScenario scenario =
      sim::MakeScenario(*config, emulation.map_yaml, "depart-return", emulation.seed);
  // Ground truth on a clock started with the run's: the same timeline within microseconds.
  truth_clock_ = std::make_unique<live::HostClock>(emulation.speed);
  player_ = std::make_unique<live::SimDevicePlayer>(
      *config, scenario, emulation.seed, config->live.radar_devices, config->live.kobuki_device,
      emulation.speed, live::EmulatorFaults{}, [c = truth_clock_.get()] { return c->Now(); },
      emulation.duration_s);
  options->ground_truth = [p = player_.get()] { return p->ground_truth(); };
  player_->Start();
  watcher_ = std::thread([p = player_.get(), stop] {
    while (!p->done() && !*stop) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let the tail arrive
    *stop = true;
  });
}

LiveEmulation::~LiveEmulation() {
  if (watcher_.joinable()) *stop_ = true;
  Finish();
}

void LiveEmulation::Finish() {
  if (watcher_.joinable()) watcher_.join();
  player_.reset();  // stops the devices and unplugs them: their links in <out>/dev go
  // The folder made for the links is no output of the run. (remove() leaves one not empty.)
  std::error_code ec;
  if (created_dev_dir_) std::filesystem::remove(dev_dir_, ec);
}

}  // namespace uwbsar::slam
