// The LT102 as a LinkProtocol (lt102_commands.h). On each open it runs the
// start-up sequence (lt102_startup.h: settings sent, every echo checked, `s` answered
// `r`); a failed step fails the open, so the link's reconnect, backoff and power cycle
// take over. Acquisition is polled: from the link's thread one `d` request is in flight
// at a time, paced at the echoed frame rate; an answer that does not come within
// live.lt102.frame_timeout_s is counted lost and the decoder resynchronises on the next
// 0xFF. Each raw-data answer is validated (size = total x 2 x bytes per value, samples
// per scan = the count from the echoed range, one channel, the configured format) and
// its I samples handed to the sink. With a clock, each scan is stamped by a StreamClock
// (stream_clock.h) on the radar's acquisition grid, not at the answer's arrival: what is
// periodic in polled acquisition is the radar's frame clock (it acquires at the echoed frame
// rate whether or not a `d` waits; a waiting `d` is answered as the frame is acquired). The
// frame's index on that grid comes from the request time, which the link thread takes just
// before writing, not from the arrival: a request sent before the next grid point gets that
// frame (last + 1); one sent n > 1 periods late gets the newest, last + n (the frames in
// between were overwritten at the radar). The answers' arrivals against those indices give
// the lower envelope; re-anchored at every start-up (new frame rate). Without a clock the
// sink stamps at arrival (scan.stamp_ns = 0). On a deliberate
// stop and before a power cycle the radar is stopped with `o`. Faults go to the FaultLog.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "drivers/live/device_link.h"
#include "drivers/live/live_settings.h"
#include "drivers/live/lt102_startup.h"
#include "drivers/live/stream_clock.h"
#include "slam/types.h"

namespace uwbsar::live {

/// Counts of one radar's link, for live.json.
struct Lt102Stats {
  long long startups = 0;  ///< completed start-up sequences
  long long startup_failures = 0;
  long long config_errors = 0;
  long long requests = 0;            ///< `d` requests sent
  long long answers = 0;             ///< `d` answers to a request in flight
  long long lost = 0;                ///< `d` requests unanswered within frame_timeout_s
  long long late_answers = 0;        ///< `d` answers after their request was given up
  long long unanswered_at_stop = 0;  ///< a `d` still in flight when the link stopped
  long long invalid_frames = 0;      ///< answers failing validation (size, samples, CRC)
  long long stops = 0;               ///< `o` sent
  Lt102ExchangeCounts exchange;      ///< start-up and stop requests, wrong / missing answers
  double answer_p50_ms = 0.0, answer_p99_ms = 0.0, answer_max_ms = 0.0;  ///< `d` to answer
  bool configured = false;
  Lt102Setup setup;               ///< of the last start-up
  long long stamp_reanchors = 0;  ///< the StreamClock's (start-ups not counted)
  /// (arrival, stamp) of the first 100000 scans stamped (host clock): for measuring the
  /// filter against an emulator's true send times.
  std::vector<std::pair<TimestampNs, TimestampNs>> stamp_trace;
};

class Lt102Driver : public LinkProtocol {
 public:
  using ScanSink = std::function<void(RadarScan&& scan)>;
  using EventSink = std::function<void(const std::string& event)>;

  /// `name` labels faults and events (e.g. "radar left").
  /// `clock` (optional) gives host-clock stamps running `clock_scale` times wall time.
  Lt102Driver(std::string name, int sensor_id, const LiveSettings& config, FaultLog* faults,
              ScanSink sink, EventSink events = {}, std::function<TimestampNs()> clock = {},
              double clock_scale = 1.0);

  bool OnOpen(SerialPort& port) override;
  double OnPoll(SerialPort& port) override;
  void OnBytes(const std::uint8_t* data, std::size_t size) override;
  void OnStop(SerialPort& port) override;
  void OnLost() override;

  /// Waits up to `timeout_s` for the first start-up to finish: true with `setup` when it
  /// did; false with `error` set when it failed with a configuration error, or empty
  /// `error` on timeout. Any thread.
  bool WaitConfigured(double timeout_s, Lt102Setup* setup, std::string* error);
  long long scans() const { return scans_; }
  /// Frames are requested only while `gate` returns true (set before the link starts): the
  /// serial source polls the radars once odometry flows, so no scan precedes the first pose.
  void set_acquisition_gate(std::function<bool()> gate) { gate_ = std::move(gate); }
  /// After the link stopped.
  Lt102Stats stats() const;

 private:
  using Clock = std::chrono::steady_clock;
  void HandleFrame(const Lt102Frame& frame);
  TimestampNs StampFrame(TimestampNs arrival_ns);

  std::string name_;
  int sensor_id_;
  LiveSettings config_;
  FaultLog* faults_;
  ScanSink sink_;
  EventSink events_;
  Lt102Exchange exchange_;
  Lt102FrameDecoder decoder_;
  Lt102FrameStats reported_;
  std::vector<Lt102Frame> frames_;
  Lt102RawData raw_;
  std::atomic<long long> scans_{0};
  std::function<TimestampNs()> clock_;
  std::function<bool()> gate_;
  double clock_scale_;
  StreamClock stamps_;
  TimestampNs request_ns_ = 0;    ///< host clock when the `d` in flight was written
  std::int64_t frame_index_ = 0;  ///< of the last frame stamped
  // Acquisition state (link thread).
  bool acquiring_ = false;
  bool in_flight_ = false;
  Clock::time_point sent_at_, next_due_;
  Clock::duration period_{};
  std::vector<double> answer_ms_;
  Lt102Stats stats_;
  // Start-up result, read by other threads.
  mutable std::mutex mutex_;
  std::condition_variable configured_cv_;
  bool have_setup_ = false;
  std::string config_error_;
};

}  // namespace uwbsar::live
