#include "drivers/live/lt102_driver.h"

#include <algorithm>
#include <cmath>

#include "slam/log.h"

namespace uwbsar::live {
namespace {

/// The next `d` goes out this fraction of a frame period early, so it waits at the radar
/// for the frame being acquired instead of arriving just after it (the stamp is the
/// answer's arrival).
constexpr double kPollLead = 0.2;

double PercentileMs(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(p / 100.0 * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

Lt102Driver::Lt102Driver(std::string name, int sensor_id, const LiveSettings& config,
                         FaultLog* faults, ScanSink sink, EventSink events,
                         std::function<TimestampNs()> clock, double clock_scale)
    : name_(std::move(name)),
      sensor_id_(sensor_id),
      config_(config),
      faults_(faults),
      sink_(std::move(sink)),
      events_(std::move(events)),
      exchange_(name_, config.live.lt102, faults),
      clock_(std::move(clock)),
      clock_scale_(clock_scale) {}

bool Lt102Driver::OnOpen(SerialPort& port) {
  OnLost();
  exchange_.Reset();
  try {
    const Lt102Setup setup = RunLt102Startup(port, exchange_, config_, name_);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stats_.setup = setup;
      stats_.configured = true;
      ++stats_.startups;
      have_setup_ = true;
    }
    configured_cv_.notify_all();
    Log(LogLevel::kInfo, name_ + ": " + setup.Describe());
    if (events_) events_(name_ + ": " + setup.Describe());
    period_ = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(1.0 / std::max(1, setup.frame_rate_fps)));
    acquiring_ = true;
    next_due_ = Clock::now();
    stamps_.Reset(1e9 / std::max(1, setup.frame_rate_fps) * clock_scale_);
    return true;
  } catch (const Lt102ConfigError& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_.config_errors;
      if (!have_setup_) config_error_ = e.what();
    }
    configured_cv_.notify_all();
    faults_->Report(name_ + ": configuration errors", e.what());
    throw;
  } catch (const SerialError&) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.startup_failures;
    throw;
  }
}

double Lt102Driver::OnPoll(SerialPort& port) {
  if (!acquiring_) return 0.05;
  if (gate_ && !in_flight_ && !gate_()) return 0.005;  // waiting for the first odometry
  const auto now = Clock::now();
  const auto timeout = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(config_.live.lt102.frame_timeout_s));
  if (in_flight_ && now - sent_at_ > timeout) {
    ++stats_.lost;
    faults_->Report(name_ + ": lost frames",
                    "no answer to 'd' within live.lt102.frame_timeout_s; resynchronising on the "
                    "next 0xFF");
    in_flight_ = false;  // a partial answer is dropped (counted broken) at the next 0xFF
    next_due_ = now;
  }
  if (!in_flight_ && now >= next_due_) {
    const std::vector<std::uint8_t> bytes = exchange_.Encode({lt102::kReadFrame, false, 0.0});
    if (!port.Write(bytes.data(), bytes.size(), 0.05)) return 0.05;  // the read sees the unplug
    ++stats_.requests;
    in_flight_ = true;
    sent_at_ = now;
    if (clock_) request_ns_ = clock_();
  }
  const auto wait = in_flight_ ? sent_at_ + timeout - now : next_due_ - now;
  return std::clamp(std::chrono::duration<double>(wait).count(), 0.0005, 0.05);
}

void Lt102Driver::OnBytes(const std::uint8_t* data, std::size_t size) {
  frames_.clear();
  decoder_.Push(data, size, &frames_);
  const Lt102FrameStats& s = decoder_.stats();
  faults_->Report(name_ + ": garbage bytes", "bytes outside frames skipped",
                  s.garbage_bytes - reported_.garbage_bytes);
  faults_->Report(name_ + ": broken frames", "frames dropped, resynchronised on the next 0xFF",
                  s.broken_frames - reported_.broken_frames);
  reported_ = s;
  for (const Lt102Frame& frame : frames_) HandleFrame(frame);
}

void Lt102Driver::HandleFrame(const Lt102Frame& frame) {
  if (frame.code != lt102::kReadFrame) {
    faults_->Report(
        name_ + ": other frames",
        "a frame starting with " + Lt102CommandLabel(frame.code) + " during acquisition ignored");
    return;
  }
  const auto now = Clock::now();
  const TimestampNs arrival_ns = clock_ ? clock_() : 0;
  const bool answered = in_flight_;
  if (in_flight_) {
    ++stats_.answers;
    answer_ms_.push_back(std::chrono::duration<double, std::milli>(now - sent_at_).count());
    in_flight_ = false;
    next_due_ = now + std::chrono::duration_cast<Clock::duration>(period_ * (1.0 - kPollLead));
  } else {
    ++stats_.late_answers;  // still a valid frame: delivered
  }
  std::vector<std::uint8_t> payload;
  std::string error;
  const Lt102Setup& setup = stats_.setup;
  const int format = config_.live.lt102.sample_format;
  const bool decoded = exchange_.StripCrc(frame, &payload, &error) &&
                       DecodeLt102RawData(payload.data(), payload.size(), &raw_, &error);
  if (!decoded) {
    // `error` says why
  } else if (raw_.samples_per_scan != setup.samples_per_scan) {
    error = "raw-data samples_per_scan " + std::to_string(raw_.samples_per_scan) +
            ", the echoed range gives " + std::to_string(setup.samples_per_scan);
  } else if (raw_.channels != 1) {
    error = "raw-data message of " + std::to_string(raw_.channels) +
            " channels (total / per scan), live.lt102.channel gives one";
  } else if (raw_.format != format) {
    error = "raw-data sample format " + std::to_string(raw_.format) +
            ", live.lt102.sample_format is " + std::to_string(format);
  }
  if (!error.empty()) {
    ++stats_.invalid_frames;
    faults_->Report(name_ + ": invalid raw-data messages", error);
    return;
  }
  RadarScan scan;
  scan.sensor_id = sensor_id_;
  scan.samples.assign(raw_.i.begin(), raw_.i.begin() + raw_.samples_per_scan);
  if (clock_) {
    scan.stamp_ns = StampFrame(arrival_ns);
    if (answered) {
      // Pace the next `d` on the radar's frame grid, kPollLead of a period before its next
      // frame, not on this answer's arrival: a late answer does not push the next request
      // past the frame (which would then wait at the radar and arrive up to a period late,
      // a delay the envelope cannot tell from the clock).
      const double ahead_ns = static_cast<double>(stamps_.Predict(frame_index_ + 1) - arrival_ns) -
                              kPollLead * stamps_.ns_per_unit();
      const double period_s = std::chrono::duration<double>(period_).count();
      const double wait_s = std::clamp(ahead_ns * 1e-9 / clock_scale_, 0.0, period_s);
      next_due_ =
          now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(wait_s));
    }
  }
  ++scans_;
  sink_(std::move(scan));
}

TimestampNs Lt102Driver::StampFrame(TimestampNs arrival_ns) {
  std::int64_t k = 0;
  if (stamps_.anchored()) {
    // Grid points after the last frame up to the request: 0 when the `d` was sent before
    // the next one (it waited for it), n when it went out n periods late.
    const double since_ns = static_cast<double>(request_ns_ - stamps_.Predict(frame_index_));
    const auto late = static_cast<std::int64_t>(std::floor(since_ns / stamps_.ns_per_unit()));
    k = frame_index_ + std::max<std::int64_t>(1, late);
  }
  frame_index_ = k;
  const TimestampNs stamp = stamps_.Stamp(k, arrival_ns);
  if (stats_.stamp_trace.size() < 100000) stats_.stamp_trace.push_back({arrival_ns, stamp});
  stats_.stamp_reanchors = stamps_.reanchors();
  return stamp;
}

void Lt102Driver::OnStop(SerialPort& port) {
  if (!port.is_open()) return;
  // Let the answer in flight arrive first, so that the first frame after `o` is its echo.
  const auto end =
      sent_at_ + std::chrono::duration_cast<Clock::duration>(
                     std::chrono::duration<double>(config_.live.lt102.frame_timeout_s));
  std::uint8_t buffer[4096];
  while (acquiring_ && in_flight_ && Clock::now() < end) {
    std::size_t n = 0;
    const auto status = port.Read(buffer, sizeof(buffer), 0.005, &n);
    if (status == SerialPort::ReadStatus::kDisconnected) return;
    if (status == SerialPort::ReadStatus::kData) OnBytes(buffer, n);
  }
  if (acquiring_ && in_flight_) ++stats_.unanswered_at_stop;
  acquiring_ = false;
  in_flight_ = false;
  try {
    ++stats_.stops;
    exchange_.Ask(port, {lt102::kStop, false, 0.0});
  } catch (const SerialError& e) {
    faults_->Report(name_ + ": stop not acknowledged", e.what());
  }
}

void Lt102Driver::OnLost() {
  decoder_.Reset();
  acquiring_ = false;
  in_flight_ = false;
}

bool Lt102Driver::WaitConfigured(double timeout_s, Lt102Setup* setup, std::string* error) {
  std::unique_lock<std::mutex> lock(mutex_);
  configured_cv_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                          [this] { return have_setup_ || !config_error_.empty(); });
  error->clear();
  if (have_setup_) {
    *setup = stats_.setup;
    return true;
  }
  *error = config_error_;
  return false;
}

Lt102Stats Lt102Driver::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  Lt102Stats s = stats_;
  s.exchange = exchange_.counts();
  s.answer_p50_ms = PercentileMs(answer_ms_, 50);
  s.answer_p99_ms = PercentileMs(answer_ms_, 99);
  s.answer_max_ms =
      answer_ms_.empty() ? 0.0 : *std::max_element(answer_ms_.begin(), answer_ms_.end());
  return s;
}

}  // namespace uwbsar::live
