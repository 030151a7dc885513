#include "drivers/live/stream_clock.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace uwbsar::live {

void StreamClock::Reset(double nominal_ns_per_unit) {
  if (nominal_ns_per_unit > 0) options_.nominal_ns_per_unit = nominal_ns_per_unit;
  points_.clear();
  late_count_ = 0;
}

void StreamClock::Anchor(std::int64_t x, TimestampNs arrival_ns) {
  if (!points_.empty() || stamped_any_) ++reanchors_;
  points_.clear();
  late_count_ = 0;
  x0_ = x;
  a0_ = arrival_ns;
  points_.push_back({0.0, 0.0});
  Fit();
}

TimestampNs StreamClock::Predict(std::int64_t x) const {
  return a0_ +
         static_cast<TimestampNs>(std::llround(alpha_ + beta_ * static_cast<double>(x - x0_)));
}

TimestampNs StreamClock::Stamp(std::int64_t x, TimestampNs arrival_ns) {
  if (points_.empty() || x <= last_x_ || x - last_x_ > options_.gap_units) {
    Anchor(x, arrival_ns);
  } else {
    const double residual_ns = static_cast<double>(arrival_ns - Predict(x));
    late_count_ = residual_ns > options_.late_tolerance_ns ? late_count_ + 1 : 0;
    const bool settled = static_cast<int>(points_.size()) >= options_.settled;
    if ((settled && residual_ns < -options_.early_tolerance_ns) ||
        late_count_ >= options_.late_run) {
      Anchor(x, arrival_ns);
    } else {
      points_.push_back({static_cast<double>(x - x0_), static_cast<double>(arrival_ns - a0_)});
      while (static_cast<int>(points_.size()) > std::max(2, options_.window)) points_.pop_front();
      Fit();
    }
  }
  last_x_ = x;
  // Arrivals are in order, so the previous stamp (<= the previous arrival) leaves room.
  TimestampNs stamp = Predict(x);
  if (stamped_any_) stamp = std::max(stamp, last_stamp_ns_ + 1);
  stamp = std::min(stamp, arrival_ns);
  stamped_any_ = true;
  last_stamp_ns_ = stamp;
  return stamp;
}

void StreamClock::Fit() {
  const double nominal = options_.nominal_ns_per_unit;
  const double lo = nominal * (1.0 - options_.max_skew), hi = nominal * (1.0 + options_.max_skew);
  // Lower convex hull (x increasing: Andrew's monotone chain, lower half).
  std::vector<Point> hull;
  hull.reserve(points_.size());
  double mean_x = 0.0;
  for (const Point& p : points_) {
    mean_x += p.x;
    while (hull.size() >= 2) {
      const Point& o = hull[hull.size() - 2];
      const Point& m = hull.back();
      const double cross = (m.x - o.x) * (p.a - o.a) - (m.a - o.a) * (p.x - o.x);
      if (cross > 0) break;  // a left turn keeps m on the lower hull
      hull.pop_back();
    }
    hull.push_back(p);
  }
  mean_x /= static_cast<double>(points_.size());
  double beta = nominal;
  for (std::size_t i = 0; i + 1 < hull.size(); ++i) {
    if (hull[i].x <= mean_x && mean_x <= hull[i + 1].x && hull[i + 1].x > hull[i].x) {
      beta = (hull[i + 1].a - hull[i].a) / (hull[i + 1].x - hull[i].x);
      break;
    }
  }
  beta_ = std::clamp(beta, lo, hi);
  // The highest line of that slope under every point.
  double alpha = points_.front().a - beta_ * points_.front().x;
  for (const Point& p : points_) alpha = std::min(alpha, p.a - beta_ * p.x);
  alpha_ = alpha;
}

}  // namespace uwbsar::live
