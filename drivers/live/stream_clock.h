// Passive synchronisation of a periodic serial stream (a minimum-delay / lower-envelope
// filter). A frame at source coordinate x (a frame index on the device's acquisition grid,
// or the device's own millisecond counter) is sent at true time alpha + beta * x and
// arrives at a = alpha + beta * x + d with a delay d >= 0 (transfer, then however long the
// scheduler kept the reading thread waiting). The lower envelope of the arrivals is the
// device clock: over a sliding window the filter fits the line under every point that
// minimises the summed delay (an edge of the points' lower convex hull, the one spanning
// the mean x; Moon, Skelly and Towsley's skew estimator), with its slope kept within
// `max_skew` of the nominal period, and stamps each frame on that line. Scheduler
// jitter only ever adds delay, so it moves single points up, not the envelope.
// Re-anchoring (window cleared, the next frame starts the line again): after Reset()
// (reconnect, new frame rate), after a gap in x longer than `gap_units`, when a frame
// arrives more than `early_tolerance_ns` before a settled line (the device clock jumped or
// ran faster), and when `late_run` frames in a row arrive more than `late_tolerance_ns` after
// it (it jumped later or runs slower). Stamps never exceed the arrival and increase
// strictly within the stream.
#pragma once

#include <cstdint>
#include <deque>

#include "core/types.h"

namespace uwbsar::live {

struct StreamClockOptions {
  double nominal_ns_per_unit = 1e7;  ///< expected period per unit of x (100 frames/s: 1e7)
  double max_skew = 0.01;            ///< slope kept within nominal * (1 +- max_skew)
  int window = 256;                  ///< points in the fit
  std::int64_t gap_units = 200;      ///< a jump in x beyond this re-anchors
  /// With at least `settled` points, an arrival this far before the line re-anchors
  /// (before that, early arrivals just lower the envelope).
  double early_tolerance_ns = 20e6;
  int settled = 16;
  double late_tolerance_ns = 200e6;  ///< arrivals this far after the line ...
  int late_run = 200;                ///< ... this many in a row re-anchor
};

class StreamClock {
 public:
  explicit StreamClock(const StreamClockOptions& options = {}) : options_(options) {}

  /// The stamp of the frame at `x` (increasing within the stream) that arrived at
  /// `arrival_ns`.
  TimestampNs Stamp(std::int64_t x, TimestampNs arrival_ns);
  /// The next frame anchors anew (reconnect, frame-rate change). `nominal_ns_per_unit` > 0
  /// replaces the nominal period.
  void Reset(double nominal_ns_per_unit = 0.0);

  /// The line's stamp for `x` (after at least one frame).
  TimestampNs Predict(std::int64_t x) const;
  double ns_per_unit() const { return beta_; }
  long long reanchors() const { return reanchors_; }
  bool anchored() const { return !points_.empty(); }

 private:
  struct Point {
    double x, a;  ///< relative to x0_, a0_
  };
  void Fit();
  void Anchor(std::int64_t x, TimestampNs arrival_ns);

  StreamClockOptions options_;
  std::deque<Point> points_;
  std::int64_t x0_ = 0, last_x_ = 0;
  TimestampNs a0_ = 0, last_stamp_ns_ = 0;
  double alpha_ = 0.0, beta_ = 0.0;  ///< line: a - a0_ = alpha_ + beta_ * (x - x0_)
  int late_count_ = 0;
  long long reanchors_ = 0;
  bool stamped_any_ = false;
};

}  // namespace uwbsar::live
