#include "drivers/emulators/sim_device_player.h"

#include <chrono>
#include <cmath>
#include <random>

#include "drivers/live/kobuki_protocol.h"
#include "drivers/live/thread_priority.h"

namespace uwbsar::live {
namespace {
using Clock = std::chrono::steady_clock;
constexpr double kSpeedOfLight = 299792458.0;
constexpr std::chrono::microseconds kServePeriod{250};
}  // namespace

SimDevicePlayer::SimDevicePlayer(const EmulatorSettings& config, const sim::SimScenario& scenario,
                                 std::uint64_t seed, std::vector<std::string> radar_links,
                                 std::string kobuki_link, double speed,
                                 const EmulatorFaults& faults, std::function<std::int64_t()> clock,
                                 double max_duration_s)
    : config_(config),
      stream_(config, scenario, seed),
      speed_(speed),
      faults_(faults),
      clock_(std::move(clock)),
      duration_s_(max_duration_s > 0 ? std::min(max_duration_s, stream_.duration_s())
                                     : stream_.duration_s()),
      rng_state_(faults.seed) {
  Lt102EmulatorOptions lt102;
  lt102.bin_m = kSpeedOfLight / (2.0 * config.pulse.sampling_frequency_hz);
  lt102.carrier_mhz = faults.lt102_carrier_mhz > 0
                          ? faults.lt102_carrier_mhz
                          : static_cast<int>(std::lround(config.pulse.center_frequency_hz / 1e6));
  lt102.bandwidth_mhz = static_cast<int>(std::lround(config.pulse.bandwidth_hz / 1e6));
  lt102.adc_frequency = static_cast<int>(std::lround(config.pulse.sampling_frequency_hz / 1e6));
  lt102.crc = faults.lt102_crc;
  lt102.wrong_echo_code = faults.lt102_wrong_echo_code;
  lt102.missing_answer_code = faults.lt102_missing_answer_code;
  lt102.missing_answer_times = faults.lt102_missing_answer_times;
  lt102.bad_size_every = faults.lt102_bad_size_every;
  lt102.corrupt_fraction = faults.corrupt_fraction;
  lt102.actual_frame_rate_fps = faults.lt102_actual_frame_rate_fps;
  lt102.hold_d_until_next_frame = faults.lt102_hold_d_until_next_frame;
  for (const std::string& link : radar_links) {
    lt102.seed = faults.seed + 1000 * radars_.size();
    radars_.push_back(std::make_unique<Lt102Emulator>(link, lt102));
  }
  kobuki_ = std::make_unique<PtyDevice>(kobuki_link);
}

SimDevicePlayer::~SimDevicePlayer() { Stop(); }

void SimDevicePlayer::Start() {
  thread_ = std::thread([this] { Loop(); });
}

void SimDevicePlayer::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

std::vector<OdometrySample> SimDevicePlayer::ground_truth() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ground_truth_;
}

EmulatorCounts SimDevicePlayer::counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  EmulatorCounts c = counts_;
  for (const auto& radar : radars_) {
    const Lt102EmulatorCounts r = radar->counts();
    c.scans_sent += r.frames_answered;
    c.frames_acquired += r.frames_acquired;
    c.frames_overwritten += r.frames_overwritten;
    c.frames_repeated += r.frames_repeated;
    c.frames_missed += r.frames_missed;
    c.frames_corrupted += r.frames_corrupted;
    c.bytes_dropped += r.bytes_dropped;
  }
  return c;
}

void ConfigureLiveForEmulation(const SimulatorConfig& simulator, double speed, LiveConfig* live) {
  live->lt102.frame_rate_fps = static_cast<int>(std::lround(simulator.radar.rate_hz * speed));
}

std::vector<std::vector<TimestampNs>> SimDevicePlayer::scan_send_ns() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return scan_send_ns_;
}

void SimDevicePlayer::SendScan(int radar, const RadarScan& scan, Clock::time_point due) {
  {
    // The scan's true time on the host clock: when the simulated run says it was acquired
    // (this thread may be late: the frame is then handed out late, not acquired late).
    const TimestampNs now =
        clock_() -
        static_cast<TimestampNs>(std::llround(
            static_cast<double>(
                std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - due).count()) *
            speed_));
    std::lock_guard<std::mutex> lock(mutex_);
    if (scan_send_ns_.size() <= static_cast<std::size_t>(radar)) {
      scan_send_ns_.resize(static_cast<std::size_t>(radar) + 1);
    }
    scan_send_ns_[static_cast<std::size_t>(radar)].push_back(now);
  }
  radars_[static_cast<std::size_t>(radar)]->Acquire(
      scan.samples, config_.radars[static_cast<std::size_t>(radar)].range_offset_m);
}

void SimDevicePlayer::SendOdometry(TimestampNs sim_stamp_ns, const OdometrySample& odometry) {
  // Recover the wheel ticks behind the simulated base's midpoint integration.
  const SimOdometryConfig& o = config_.simulator.odometry;
  const double metres_per_tick = 2.0 * M_PI * o.wheel_radius_m / o.ticks_per_revolution;
  const Pose2& p = odometry.T_world_robot;
  if (have_last_odometry_) {
    const double dyaw = NormalizeAngle(p.yaw_rad - last_odometry_.yaw_rad);
    const double mid = last_odometry_.yaw_rad + 0.5 * dyaw;
    const double dx = p.x_m - last_odometry_.x_m, dy = p.y_m - last_odometry_.y_m;
    const double d = dx * std::cos(mid) + dy * std::sin(mid);
    const double wheel[2] = {d - 0.5 * dyaw * o.wheelbase_m, d + 0.5 * dyaw * o.wheelbase_m};
    for (int k = 0; k < 2; ++k) ticks_[k] += std::llround(wheel[k] / metres_per_tick);
  }
  have_last_odometry_ = true;
  last_odometry_ = p;
  const double rel_s = NsToSeconds(sim_stamp_ns - stream_.start_ns());
  if (faults_.stall_at_s >= 0 && rel_s >= faults_.stall_at_s &&
      rel_s < faults_.stall_at_s + faults_.stall_for_s) {
    return;  // the base stays silent; its encoders keep counting
  }
  KobukiBasicSensorData data;
  data.timestamp_ms = static_cast<std::uint16_t>((sim_stamp_ns / 1000000) & 0xFFFF);
  std::int64_t jump = 0;
  if (faults_.encoder_jump_at_s >= 0 && rel_s >= faults_.encoder_jump_at_s && jump_ticks_ == 0) {
    jump_ticks_ = 20000;  // one glitched packet, then the true counts again
    jump = jump_ticks_;
  }
  data.left_encoder = static_cast<std::uint16_t>((ticks_[0] + jump) & 0xFFFF);
  data.right_encoder = static_cast<std::uint16_t>((ticks_[1] + jump) & 0xFFFF);
  data.battery = 160;
  std::vector<std::uint8_t> packet = EncodeKobukiPacket(data);
  std::mt19937_64 rng(rng_state_++);
  const bool corrupt = std::uniform_real_distribution<double>(0, 1)(rng) < faults_.corrupt_fraction;
  if (corrupt) packet[3 + rng() % (packet.size() - 4)] ^= 0x5A;
  const std::size_t written = kobuki_->Write(packet);
  std::lock_guard<std::mutex> lock(mutex_);
  ++counts_.packets_sent;
  if (corrupt) ++counts_.packets_corrupted;
  counts_.bytes_dropped += static_cast<long long>(packet.size() - written);
}

void SimDevicePlayer::Loop() {
  // The emulated devices stand for hardware that does not share the host's CPU.
  RequestRealtimeOrWarn(config_.live.driver_priority, "device emulator");
  const auto t0 = Clock::now();
  sim::SimMessage msg;
  while (!stop_ && stream_.Next(&msg)) {
    const double rel_s = NsToSeconds(msg.stamp_ns - stream_.start_ns());
    if (rel_s > duration_s_) break;
    const auto target = t0 + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(rel_s / speed_));
    // Requests are answered within kServePeriod (a module on USB answers within a USB
    // frame): a `d` waits at most that long for the latest frame.
    while (true) {
      for (auto& radar : radars_) radar->Serve();
      const auto now = Clock::now();
      if (now >= target || stop_) break;
      std::this_thread::sleep_for(std::min<Clock::duration>(target - now, kServePeriod));
    }
    if (faults_.unplug_at_s >= 0 && faults_.unplug_radar < static_cast<int>(radars_.size())) {
      Lt102Emulator& dev = *radars_[static_cast<std::size_t>(faults_.unplug_radar)];
      const bool out =
          rel_s >= faults_.unplug_at_s && rel_s < faults_.unplug_at_s + faults_.unplug_for_s;
      if (out && dev.plugged()) {
        dev.Unplug();
      } else if (!out && !dev.plugged()) {
        dev.Plug();
      }
    }
    switch (msg.kind) {
      case sim::SimMessage::Kind::kGroundTruth: {
        OdometrySample truth = msg.pose;
        truth.stamp_ns = clock_();
        std::lock_guard<std::mutex> lock(mutex_);
        ground_truth_.push_back(truth);
        break;
      }
      case sim::SimMessage::Kind::kOdometry:
        SendOdometry(msg.stamp_ns, msg.pose);
        break;
      case sim::SimMessage::Kind::kRadarScan:
        if (msg.scan.sensor_id < static_cast<int>(radars_.size()))
          SendScan(msg.scan.sensor_id, msg.scan, target);
        break;
      case sim::SimMessage::Kind::kLaserScan:
        break;
    }
  }
  done_ = true;
  // The radars keep answering (the drivers' stop `o`) until the player is stopped.
  while (!stop_) {
    for (auto& radar : radars_) radar->Serve();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace uwbsar::live
