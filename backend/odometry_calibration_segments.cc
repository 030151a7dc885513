#include "backend/odometry_calibration_segments.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "backend/se2_edge_cost.h"

namespace uwbsar {
namespace calibration_fit {
namespace {

/// Ground truth at `stamp_ns`, interpolated; false when no truth sample lies within `max_gap_ns`
/// on both sides.
class TruthAt {
 public:
  TruthAt(const std::vector<OdometrySample>& truth, TimestampNs max_gap_ns)
      : truth_(truth), max_gap_ns_(max_gap_ns) {}

  bool operator()(TimestampNs stamp_ns, Pose2* pose) {
    while (next_ < truth_.size() && truth_[next_].stamp_ns < stamp_ns) ++next_;
    if (next_ < truth_.size() && truth_[next_].stamp_ns == stamp_ns) {
      *pose = truth_[next_].T_world_robot;
      return true;
    }
    if (next_ >= truth_.size() || next_ == 0) return false;
    const OdometrySample& a = truth_[next_ - 1];
    const OdometrySample& b = truth_[next_];
    if (stamp_ns - a.stamp_ns > max_gap_ns_ || b.stamp_ns - stamp_ns > max_gap_ns_) return false;
    const double t = b.stamp_ns == a.stamp_ns ? 0.0
                                              : static_cast<double>(stamp_ns - a.stamp_ns) /
                                                    static_cast<double>(b.stamp_ns - a.stamp_ns);
    *pose = Interpolate(a.T_world_robot, b.T_world_robot, t);
    return true;
  }

 private:
  const std::vector<OdometrySample>& truth_;
  TimestampNs max_gap_ns_;
  std::size_t next_ = 0;
};

}  // namespace

std::vector<Segment> CutSegments(const std::vector<OdometrySample>& odometry,
                                 const std::vector<OdometrySample>& ground_truth,
                                 const CalibrationFitOptions& options) {
  TruthAt truth_at(ground_truth, static_cast<TimestampNs>(options.max_truth_gap_s * 1e9));
  std::vector<Segment> segments;
  Segment current;
  Pose2 truth_start;
  const OdometrySample* prev = nullptr;  // null: no segment open
  const TimestampNs t0 = odometry.empty() ? 0 : odometry.front().stamp_ns;
  for (const OdometrySample& o : odometry) {
    Pose2 truth;
    if (!truth_at(o.stamp_ns, &truth)) {
      prev = nullptr;  // a gap in the truth: start again after it
      continue;
    }
    if (prev == nullptr) {
      current = Segment{};
      truth_start = truth;
      prev = &o;
      continue;
    }
    const Pose2 increment = Between(prev->T_world_robot, o.T_world_robot);
    current.increments.push_back(increment);
    current.travels.push_back(TravelOf(increment));
    current.travels.back().duration_s = NsToSeconds(o.stamp_ns - prev->stamp_ns);
    current.path_m += current.travels.back().path_m;
    current.turn_rad += increment.yaw_rad;
    current.duration_s += current.travels.back().duration_s;
    prev = &o;
    // A spin in place travels no path: its turn ends the segment (1 rad keeps it unambiguous).
    // The small margin keeps a path of n equal steps from missing the end by rounding.
    if (current.path_m < options.segment_m - 1e-9 && std::abs(current.turn_rad) < 1.0) continue;
    current.truth = Between(truth_start, truth);
    current.middle_s = NsToSeconds(o.stamp_ns - t0) - 0.5 * current.duration_s;
    segments.push_back(std::move(current));
    current = Segment{};
    truth_start = truth;
  }
  return segments;
}

Eigen::Matrix3d SegmentSqrtInformation(const Segment& s, const BackendConfig& config) {
  const double d = std::max(s.path_m, config.odometry_min_distance_m);
  return *SqrtInformation(Eigen::Vector3d(config.odometry_xy_information / d,
                                          config.odometry_xy_information / d,
                                          config.odometry_yaw_information / d)
                              .asDiagonal());
}

void SegmentErrors(const std::vector<Segment>& segments, const OdometryCalibration& c,
                   const std::vector<double>& bias, double* xy_rms_m, double* yaw_rms_rad) {
  double xy = 0.0, yaw = 0.0;
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (std::size_t i = 0; i < segments.size(); ++i) {
    double e[3];
    SegmentCost(&segments[i], identity)(c.data(), &bias[i], e);
    xy += e[0] * e[0] + e[1] * e[1];
    yaw += e[2] * e[2];
  }
  const double n = std::max<double>(1.0, static_cast<double>(segments.size()));
  *xy_rms_m = std::sqrt(xy / n);
  *yaw_rms_rad = std::sqrt(yaw / n);
}

}  // namespace calibration_fit
}  // namespace uwbsar
