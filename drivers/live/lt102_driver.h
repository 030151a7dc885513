// The LT102 as a LinkProtocol (lt102_commands.h). On each open it runs the
// start-up sequence (lt102_startup.h: settings sent, every echo checked, `s` answered
// `r`); a failed step fails the open, so the link's reconnect, backoff and power cycle
// take over. Acquisition is polled: from the link's thread one `d` request is in flight
// at a time; an answer that does not come within live.lt102.frame_timeout_s is counted lost
// and the decoder resynchronises on the next 0xFF. Each raw-data answer is validated (size
// = total x 2 x bytes per value, samples per scan = the count from the echoed range, one
// channel, the configured format).
//
// The radar behaviour assumed (ARIA Sensing's public toolbox; docs/live.md, "Polled
// acquisition"): it acquires at its actual frame rate (the `f` answer) whether or not a `d`
// waits, and answers `d` with its latest frame, so a `d` sent before the next frame returns
// the same frame again and one sent more than a period late skips frames. The documentation
// does not say whether an early `d` is answered at once or held until the next frame: both
// work here.
// - Frame identity: an answer whose payload equals the last delivered frame's byte for byte
//   is that frame again (frame noise makes two acquisitions differ): dropped, counted
//   `frames_repeated`; it is never handed to the sink. (The header's 12-bit elapsed-time
//   field is not documented as a per-frame counter and is not used.)
// - Pacing by the radar's frame clock: the driver keeps an estimate of the acquisition
//   time of the last frame (the grid, on the steady clock) and polls at grid + period +
//   phase. Each new frame's acquisition lies before its answer's arrival less the smallest
//   request-to-answer delay seen (the transfer time), which tightens the grid from above;
//   the phase creeps earlier frame by frame (fast until the first early poll after an open,
//   then slowly), and a poll found early (a repeat, or an answer held well beyond the
//   transfer time) backs it off, so the polls stay locked just after the radar's frames.
// - Frame index and misses: a new frame's index is the grid points up to the request's
//   write time (at least one past the last frame); indices skipped are counted
//   `frames_missed` (the phase then advances a little).
// - Stamps: with a clock, each scan is stamped by a StreamClock (stream_clock.h) fed the
//   frame index and that upper bound of its acquisition time (arrival less the transfer
//   time), whose lower envelope is the radar's acquisition grid: the frame's acquisition
//   time, not the poll's or the answer's. Without a clock the sink stamps at arrival
//   (scan.stamp_ns = 0).
// On a deliberate stop and before a power cycle the radar is stopped with `o`. Faults go to
// the FaultLog.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "core/types.h"
#include "drivers/live/device_link.h"
#include "drivers/live/live_settings.h"
#include "drivers/live/lt102_startup.h"
#include "drivers/live/stream_clock.h"

namespace uwbsar::live {

/// Counts of one radar's link, for live.json.
struct Lt102Stats {
  long long startups = 0;  ///< completed start-up sequences
  long long startup_failures = 0;
  long long config_errors = 0;
  long long requests = 0;            ///< `d` requests sent
  long long answers = 0;             ///< `d` answers to a request in flight
  long long frames_delivered = 0;    ///< distinct frames handed to the sink (scans)
  long long frames_repeated = 0;     ///< answers repeating the last delivered frame: dropped
  long long frames_missed = 0;       ///< frame indices skipped between delivered frames
  double acquiring_s = 0.0;          ///< wall time from the first `d` to the last answer
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
  /// Frame identity and pacing for a valid answer; false for a repeat (not delivered).
  /// `index` is the frame's index on the radar's grid.
  bool TrackFrame(Clock::time_point arrival, bool answered, std::int64_t* index);
  /// A poll found early (a repeat, or an answer the radar held): the phase backs off and the
  /// grid moves after `request`; true. False (nothing changed) for a repeat well after the
  /// predicted frame: that frame is late, the poll was not early.
  bool BackOff(Clock::time_point request);
  Clock::time_point NextPoll() const;

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
  // Acquisition state (link thread).
  bool acquiring_ = false;
  bool in_flight_ = false;
  Clock::time_point sent_at_, next_due_, first_request_, last_answer_;
  double period_s_ = 0.01;        ///< the radar's actual frame period
  bool have_grid_ = false;        ///< a frame was delivered since the open
  Clock::time_point grid_;        ///< estimated acquisition time of the last delivered frame
  std::int64_t frame_index_ = 0;  ///< of the last delivered frame
  double phase_s_ = 0.0;          ///< the next poll goes out at grid_ + period + phase_s_
  bool phase_locked_ = false;     ///< a poll was found early since the open: slow creep
  double min_latency_s_ = -1.0;   ///< smallest request-to-answer delay since the open
  std::vector<std::uint8_t> last_payload_;  ///< of the last delivered frame
  int repeats_of_frame_ = 0;                ///< answers repeating it so far
  std::vector<double> answer_ms_;
  Lt102Stats stats_;
  // Start-up result, read by other threads.
  mutable std::mutex mutex_;
  std::condition_variable configured_cv_;
  bool have_setup_ = false;
  std::string config_error_;
};

}  // namespace uwbsar::live
