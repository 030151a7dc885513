#include "drivers/live/sim_device_player.h"

#include <chrono>
#include <cmath>
#include <random>

#include "drivers/live/kobuki_protocol.h"
#include "drivers/live/lt102_protocol.h"

namespace uwbsar::live {
namespace {
using Clock = std::chrono::steady_clock;
}

SimDevicePlayer::SimDevicePlayer(const Config& config, const sim::SimScenario& scenario,
                                 std::uint64_t seed, std::vector<std::string> radar_links,
                                 std::string kobuki_link, double speed, int lt102_format,
                                 const EmulatorFaults& faults, std::function<std::int64_t()> clock,
                                 double max_duration_s)
    : config_(config),
      stream_(config, scenario, seed),
      speed_(speed),
      format_(lt102_format),
      faults_(faults),
      clock_(std::move(clock)),
      duration_s_(max_duration_s > 0 ? std::min(max_duration_s, stream_.duration_s())
                                     : stream_.duration_s()),
      rng_state_(faults.seed) {
  for (const std::string& link : radar_links) {
    radars_.push_back(std::make_unique<PtyDevice>(link));
    streaming_.push_back(false);
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

void SimDevicePlayer::WaitDone() {
  if (thread_.joinable()) thread_.join();
}

std::vector<OdometrySample> SimDevicePlayer::ground_truth() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ground_truth_;
}

EmulatorCounts SimDevicePlayer::counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

void SimDevicePlayer::ServeCommands(int radar) {
  PtyDevice& dev = *radars_[static_cast<std::size_t>(radar)];
  const std::vector<std::uint8_t> bytes = dev.ReadAvailable();
  if (bytes.empty()) return;
  static thread_local std::vector<Lt102FrameDecoder> decoders;
  decoders.resize(radars_.size());
  std::vector<Lt102Frame> frames;
  decoders[static_cast<std::size_t>(radar)].Push(bytes.data(), bytes.size(), &frames);
  for (const Lt102Frame& f : frames) {
    for (const std::string& c : config_.live.lt102_start_commands) {
      const Lt102Frame start = ParseLt102Command(c);
      if (f.code == start.code && f.payload == start.payload) {
        streaming_[static_cast<std::size_t>(radar)] = true;
      }
    }
    for (const std::string& c : config_.live.lt102_stop_commands) {
      const Lt102Frame stop = ParseLt102Command(c);
      if (f.code == stop.code && f.payload == stop.payload) {
        streaming_[static_cast<std::size_t>(radar)] = false;
      }
    }
  }
}

void SimDevicePlayer::SendScan(int radar, const RadarScan& scan) {
  PtyDevice& dev = *radars_[static_cast<std::size_t>(radar)];
  if (!dev.plugged() || !streaming_[static_cast<std::size_t>(radar)]) return;
  const std::vector<float> q(scan.samples.size(), 0.0f);
  const std::vector<std::uint8_t> payload =
      EncodeLt102RawData(format_, static_cast<int>(scan.samples.size()), 250, scan.samples, q);
  std::vector<std::uint8_t> frame;
  EncodeLt102Frame(static_cast<std::uint8_t>(config_.live.lt102_raw_data_code), payload.data(),
                   payload.size(), &frame);
  std::mt19937_64 rng(rng_state_++);
  const bool corrupt = std::uniform_real_distribution<double>(0, 1)(rng) < faults_.corrupt_fraction;
  if (corrupt) {
    switch (rng() % 3) {
      case 0: {  // garbage before the frame
        std::vector<std::uint8_t> garbage(20);
        for (auto& b : garbage) b = static_cast<std::uint8_t>(rng() & 0x7F);
        frame.insert(frame.begin(), garbage.begin(), garbage.end());
        // and the frame itself cut short, so the scan is lost visibly
        frame.resize(frame.size() / 2);
        break;
      }
      case 1:  // truncated: the end byte never comes
        frame.resize(frame.size() / 2);
        break;
      default:  // an invalid escape in the middle
        frame[frame.size() / 2] = 0x80;
        frame[frame.size() / 2 + 1] = 0x42;
        break;
    }
  }
  const std::size_t written = dev.Write(frame);
  std::lock_guard<std::mutex> lock(mutex_);
  ++counts_.scans_sent;
  if (corrupt) ++counts_.frames_corrupted;
  counts_.bytes_dropped += static_cast<long long>(frame.size() - written);
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
  const auto t0 = Clock::now();
  sim::SimMessage msg;
  while (!stop_ && stream_.Next(&msg)) {
    const double rel_s = NsToSeconds(msg.stamp_ns - stream_.start_ns());
    if (rel_s > duration_s_) break;
    const auto target = t0 + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(rel_s / speed_));
    while (true) {
      for (int r = 0; r < static_cast<int>(radars_.size()); ++r) ServeCommands(r);
      const auto now = Clock::now();
      if (now >= target || stop_) break;
      std::this_thread::sleep_for(
          std::min<Clock::duration>(target - now, std::chrono::milliseconds(2)));
    }
    if (faults_.unplug_at_s >= 0 && faults_.unplug_radar < static_cast<int>(radars_.size())) {
      PtyDevice& dev = *radars_[static_cast<std::size_t>(faults_.unplug_radar)];
      const bool out =
          rel_s >= faults_.unplug_at_s && rel_s < faults_.unplug_at_s + faults_.unplug_for_s;
      if (out && dev.plugged()) {
        dev.Unplug();
        streaming_[static_cast<std::size_t>(faults_.unplug_radar)] = false;
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
          SendScan(msg.scan.sensor_id, msg.scan);
        break;
      case sim::SimMessage::Kind::kLaserScan:
        break;
    }
  }
  done_ = true;
}

}  // namespace uwbsar::live
