#include "drivers/live/lt102_driver.h"

#include <algorithm>
#include <cmath>

#include "core/log.h"

namespace uwbsar::live {
namespace {

// Phase control, in frame periods (see lt102_driver.h). The phase creeps earlier by
// kCreepFast per new frame until the first early poll after an open, then by kCreepSlow;
// an early poll backs it off by kBackOff, so about kCreepSlow / kBackOff of the polls find
// the frame not yet acquired (2 % once locked; 2-5 % measured over a run: repeats, dropped).
// A miss advances it by kAdvance.
constexpr double kInitialPhase = 0.25, kCreepFast = 0.05, kCreepSlow = 0.002, kBackOff = 0.1,
                 kAdvance = 0.02, kMinPhase = -0.5, kMaxPhase = 0.5;
/// An answer this many periods slower than the fastest one was held by the radar: the
/// poll went out before the frame (a radar that holds an early `d` instead of repeating).
constexpr double kHeldAnswer = 0.4;
/// A repeat this many periods after the predicted frame is a late frame, not an early poll.
constexpr double kLateRepeat = 0.25;
/// After a repeat the frame is asked for again this many periods later: soon after an early
/// poll, later when the frame itself is late.
constexpr double kRetryEarly = 0.05, kRetryLate = 0.25;

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
    // The radar's actual frame rate paces the polls (the `f` answer, not the rate asked).
    period_s_ = 1.0 / std::max(1, setup.frame_rate_fps);
    acquiring_ = true;
    next_due_ = Clock::now();
    have_grid_ = phase_locked_ = false;
    phase_s_ = kInitialPhase * period_s_;
    min_latency_s_ = -1.0;
    last_payload_.clear();
    repeats_of_frame_ = 0;
    stamps_.Reset(1e9 * period_s_ * clock_scale_);
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
    if (stats_.requests++ == 0) first_request_ = now;
    in_flight_ = true;
    sent_at_ = now;
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
    last_answer_ = now;
    stats_.acquiring_s = std::chrono::duration<double>(now - first_request_).count();
  } else {
    ++stats_.late_answers;  // still a valid frame: delivered unless a repeat
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
    if (answered) next_due_ = std::max(now, NextPoll());
    return;
  }
  if (!last_payload_.empty() && payload == last_payload_) {
    ++stats_.frames_repeated;  // the radar's latest frame is still the one delivered
    // Asked again soon after an early poll, a little later when the frame itself is late:
    // only the first repeat of a frame can be an early poll; more mean the next frame is late
    // (the grid would otherwise follow the retries and hide the frames a stall overwrote).
    const bool early = !answered || (repeats_of_frame_++ == 0 && BackOff(sent_at_));
    next_due_ = std::max(
        now + std::chrono::duration_cast<Clock::duration>(
                  std::chrono::duration<double>((early ? kRetryEarly : kRetryLate) * period_s_)),
        NextPoll());
    return;
  }
  last_payload_ = std::move(payload);
  repeats_of_frame_ = 0;
  std::int64_t index = 0;
  const double upper_s = TrackFrame(now, answered, &index) ? min_latency_s_ : 0.0;
  RadarScan scan;
  scan.sensor_id = sensor_id_;
  scan.samples.assign(raw_.i.begin(), raw_.i.begin() + raw_.samples_per_scan);
  if (clock_) {
    // The frame was acquired before its answer arrived less the transfer time.
    const auto acquired_ns =
        arrival_ns - static_cast<TimestampNs>(std::llround(upper_s * 1e9 * clock_scale_));
    scan.stamp_ns = stamps_.Stamp(index, acquired_ns);
    if (stats_.stamp_trace.size() < 100000) {
      stats_.stamp_trace.push_back({arrival_ns, scan.stamp_ns});
    }
    stats_.stamp_reanchors = stamps_.reanchors();
  }
  ++stats_.frames_delivered;
  ++scans_;
  sink_(std::move(scan));
}

Lt102Driver::Clock::time_point Lt102Driver::NextPoll() const {
  return grid_ + std::chrono::duration_cast<Clock::duration>(
                     std::chrono::duration<double>(period_s_ + phase_s_));
}

bool Lt102Driver::BackOff(Clock::time_point request) {
  const auto span = [](double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  // A request more than kLateRepeat of a period after the predicted frame that still finds
  // the last one is not an early poll: the frame is late at the radar (or at an emulator
  // whose thread was held up). The grid and the phase stay; the poll is simply repeated.
  if (have_grid_ && request > grid_ + span((1.0 + kLateRepeat) * period_s_)) return false;
  phase_locked_ = true;
  phase_s_ = std::min(kMaxPhase * period_s_, phase_s_ + kBackOff * period_s_);
  // The next frame is acquired after the request went out: the grid is at least that late.
  const auto earliest = request - span(period_s_);
  if (have_grid_ && grid_ < earliest) grid_ = earliest;
  return true;
}

bool Lt102Driver::TrackFrame(Clock::time_point arrival, bool answered, std::int64_t* index) {
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  const auto span = [](double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  if (!answered) {  // a late answer: no request time to place it by
    *index = ++frame_index_;
    if (have_grid_) grid_ += span(period_s_);
    return false;
  }
  const double latency_s = seconds(arrival - sent_at_);
  if (min_latency_s_ < 0 || latency_s < min_latency_s_) min_latency_s_ = latency_s;
  const auto upper = arrival - span(min_latency_s_);  // the frame was acquired before this
  if (!have_grid_) {
    have_grid_ = true;
    grid_ = upper;
    *index = frame_index_ = 0;
    next_due_ = NextPoll();
    return true;
  }
  // Grid points up to the request's write time: the frame answered is the latest of those.
  const double ahead = std::floor(seconds(sent_at_ - grid_) / period_s_);
  const auto n = std::max<std::int64_t>(1, static_cast<std::int64_t>(ahead));
  stats_.frames_missed += n - 1;
  frame_index_ += n;
  *index = frame_index_;
  grid_ += span(static_cast<double>(n) * period_s_);
  if (upper < grid_) grid_ = upper;  // tightened from above
  if (latency_s > min_latency_s_ + kHeldAnswer * period_s_) {
    BackOff(sent_at_);  // held by the radar: the poll went out before the frame
  } else {
    phase_s_ -= (phase_locked_ ? kCreepSlow : kCreepFast) * period_s_;
  }
  if (n > 1) phase_s_ -= kAdvance * period_s_;
  phase_s_ = std::clamp(phase_s_, kMinPhase * period_s_, kMaxPhase * period_s_);
  next_due_ = std::max(arrival, NextPoll());
  return true;
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
