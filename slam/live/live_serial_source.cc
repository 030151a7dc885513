// The robot's own devices as a live source: radars of live.radar_model, created through the
// factory (drivers/live/radar_driver_factory.h; the LT102 on reconnecting serial links), the
// Kobuki base on a reconnecting serial link, radar power and reset through GPIO. Each device's
// messages are stamped by its driver (drivers/live/stream_clock.h: the radar's acquisition
// grid, the base's millisecond counter), not at arrival, and put back in stamp order within
// live.reorder_window_s, so SLAM and the recording see them in the order `uwbsar map` reads
// the recording, whatever the scheduler did to the reading threads.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/errors.h"
#include "drivers/live/device_link.h"
#include "drivers/live/kobuki_driver.h"
#include "drivers/live/radar_driver_factory.h"
#include "drivers/live/radar_power.h"
#include "slam/app_config.h"
#include "slam/live/live_source.h"
#include "slam/live/stamp_order_buffer.h"

namespace uwbsar::slam {
namespace {

class SerialSource : public LiveSource {
 public:
  SerialSource(const Config& config, LiveRunOptions& options, Dispatcher* dispatcher,
               live::FaultLog* faults, live::HostClock* clock)
      : lc_(config.live),
        dispatcher_(dispatcher),
        faults_(faults),
        clock_(clock),
        order_(static_cast<std::int64_t>(config.live.reorder_window_s * 1e9),
               [this](LiveMessage&& m, bool late) { Release(std::move(m), late); }) {
    if (lc_.radar_devices.size() != config.radars.size()) {
      throw InputError("live.radar_devices lists " + std::to_string(lc_.radar_devices.size()) +
                       " devices for " + std::to_string(config.radars.size()) +
                       " radars: give one serial device per radars[] entry");
    }
    live::RequireRadarModel(lc_.radar_model);  // ConfigError naming the registered ones
    // GPIO first: a missing chip or line stops the run before anything moves.
    std::unique_ptr<live::GpioChip> chip =
        options.gpio ? std::move(options.gpio) : live::OpenConfiguredChip(lc_);
    power_ = std::make_unique<live::RadarPower>(
        std::move(chip), lc_,
        [dispatcher](const std::string& e) { dispatcher->Event("gpio: " + e); });
    power_->StartUp();

    live::LinkPolicy policy;
    policy.read_timeout_s = lc_.read_timeout_s;
    policy.reconnect_initial_s = lc_.reconnect_initial_s;
    policy.reconnect_max_s = lc_.reconnect_max_s;
    policy.power_cycle_after_failures = lc_.power_cycle_after_failures;
    policy.realtime_priority = lc_.driver_priority;
    for (std::size_t i = 0; i < config.radars.size(); ++i) {
      live::RadarDeviceArgs args;
      args.name = "radar " + config.radars[i].name;
      args.sensor_id = static_cast<int>(i);
      args.device = lc_.radar_devices[i];
      args.link = policy;
      args.link.baud = lc_.radar_baud;
      args.settings = config;
      args.faults = faults;
      args.sink = [this](RadarScan&& scan) {
        LiveMessage m;
        m.kind = Message::Kind::kRadarScan;
        m.stamp_ns = scan.stamp_ns;
        m.scan = std::move(scan);
        order_.Push(m.stamp_ns, SteadyNs(), std::move(m));
      };
      args.events = [dispatcher](const std::string& event) { dispatcher->Event(event); };
      args.clock = [clock] { return clock->Now(); };
      args.clock_scale = clock->scale();
      // Scans wait for the odometry (as over DDS): a radar acquires once the base's first
      // sample went out, so no scan is stamped before the first pose and dropped.
      args.acquisition_gate = [this] { return odometry_started_.load(); };
      if (power_->can_power_cycle(static_cast<int>(i))) {
        args.power_cycle = [power = power_.get(), i] { power->PowerCycle(static_cast<int>(i)); };
      }
      radar_names_.push_back(args.name);
      radars_.push_back(live::CreateRadar(lc_.radar_model, args));
    }
    kobuki_ = std::make_unique<live::KobukiDriver>(
        lc_, faults, [clock] { return clock->Now(); },
        [this](OdometrySample&& sample) {
          LiveMessage m;
          m.kind = Message::Kind::kOdometry;
          m.stamp_ns = sample.stamp_ns;
          m.odometry = sample;
          order_.Push(m.stamp_ns, SteadyNs(), std::move(m));
          last_odometry_ns_ = clock_->Now();
          odometry_started_ = true;
        });
    live::LinkPolicy p = policy;
    p.baud = lc_.kobuki_baud;
    kobuki_link_ =
        std::make_unique<live::DeviceLink>("kobuki", lc_.kobuki_device, p, kobuki_.get(), faults);
  }

  void Start() override {
    for (auto& radar : radars_) radar->Start();
    kobuki_link_->Start();
  }

  // Odometry stalls, clock steps, status LED (on while every link is up).
  void Poll() override {
    order_.Poll(SteadyNs());
    const double step_s = clock_->CheckStep();
    if (std::abs(step_s) >= lc_.clock_step_threshold_s) {
      faults_->Report("host clock: steps", "system clock stepped by " + std::to_string(step_s) +
                                               " s; stamps follow the monotonic clock");
    }
    const long long last = last_odometry_ns_;
    const double silent_s = last == 0 ? 0.0 : NsToSeconds(clock_->Now() - last);
    if (silent_s > lc_.odometry_stall_s && !stalled_) {
      stalled_ = true;
      faults_->Report("kobuki: odometry stalls",
                      "no odometry for " + std::to_string(lc_.odometry_stall_s) +
                          " s; SLAM waits, scans without odometry are not imaged");
    } else if (silent_s <= lc_.odometry_stall_s) {
      stalled_ = false;
    }
    const bool all_up =
        kobuki_link_->connected() &&
        std::all_of(radars_.begin(), radars_.end(), [](const auto& r) { return r->connected(); });
    if (all_up != led_) {
      power_->SetStatusLed(all_up);
      led_ = all_up;
    }
  }

  // Every radar's first start-up (all wait in parallel, up to the longest of their
  // startup_wait() in all, live.lt102.startup_wait_s for the LT102): its echoed range sets the
  // range of sample 0 and the sample count imaging uses.
  void ConfigureImaging(Config* config) override {
    double wait_s = 0.0;
    for (const auto& radar : radars_) wait_s = std::max(wait_s, radar->startup_wait().wait_s);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s);
    for (std::size_t i = 0; i < radars_.size(); ++i) {
      const double left_s = std::max(
          0.0, std::chrono::duration<double>(end - std::chrono::steady_clock::now()).count());
      live::RadarSetup setup;
      std::string error;
      RadarConfig& radar = config->radars[i];
      if (radars_[i]->WaitConfigured(left_s, &setup, &error)) {
        radar.range_offset_m = setup.range_min_m;
        radar.num_samples = setup.samples_per_scan;
        dispatcher_->Event(radar_names_[i] + ": imaging uses the echoed range: sample 0 at " +
                           std::to_string(radar.range_offset_m) + " m, " +
                           std::to_string(radar.num_samples) + " samples");
      } else if (!error.empty()) {
        throw InputError(error);
      } else {
        faults_->Report(radar_names_[i] + ": not configured before SLAM started",
                        "no start-up within " + radars_[i]->startup_wait().key +
                            "; imaging uses radars[].range_offset_m and num_samples");
      }
    }
  }

  void Stop() override {
    // The radars' stop exchanges (the LT102's `o`) run together.
    for (auto& radar : radars_) radar->RequestStop();
    kobuki_link_->RequestStop();
    for (auto& radar : radars_) radar->Stop();
    kobuki_link_->Stop();
    order_.Flush();
  }

  std::vector<std::pair<std::string, live::RadarStats>> radar_stats() const override {
    std::vector<std::pair<std::string, live::RadarStats>> out;
    for (std::size_t i = 0; i < radars_.size(); ++i) {
      out.emplace_back(radar_names_[i], radars_[i]->stats());
    }
    return out;
  }
  void ShutDown() override { power_->ShutDown(); }

  long long scans_received() const override {
    long long n = 0;
    for (const auto& r : radars_) n += r->scans();
    return n;
  }

 private:
  static std::int64_t SteadyNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  // A late message still goes to SLAM with its own stamp (as with ROS 2).
  void Release(LiveMessage&& m, bool late) {
    if (late) {
      faults_->Report("serial: late samples",
                      "a message came after later-stamped ones of another device were passed "
                      "on (more than live.reorder_window_s apart); recorded and used");
    }
    dispatcher_->PublishStamped(std::move(m));
  }

  const LiveConfig& lc_;
  Dispatcher* dispatcher_;
  live::FaultLog* faults_;
  live::HostClock* clock_;
  // What the devices' threads use, declared before the devices, which stop first.
  StampOrderBuffer<LiveMessage> order_;
  std::atomic<long long> last_odometry_ns_{0};
  std::atomic<bool> odometry_started_{false};
  std::unique_ptr<live::RadarPower> power_;
  std::vector<std::unique_ptr<live::RadarDevice>> radars_;  // each with its own link
  std::vector<std::string> radar_names_;
  std::unique_ptr<live::KobukiDriver> kobuki_;
  std::unique_ptr<live::DeviceLink> kobuki_link_;
  bool stalled_ = false, led_ = false;
};

}  // namespace

std::unique_ptr<LiveSource> MakeSerialSource(const Config& config, LiveRunOptions& options,
                                             Dispatcher* dispatcher, live::FaultLog* faults,
                                             live::HostClock* clock) {
  return std::make_unique<SerialSource>(config, options, dispatcher, faults, clock);
}

}  // namespace uwbsar::slam
