#include "slam/wall_edges.h"

#include <cmath>

namespace uwbsar::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Information along the path and in yaw: a hundred thousand times weaker than across it, so
/// that the edge leaves them to the odometry while its matrix stays positive definite.
constexpr double kWeakFraction = 1e-5;

}  // namespace

PoseGraphEdge WallEdgeFinder::MakeEdge(int a_id, int b_id, const Pose2& T_a_b_odometry,
                                       double heading_rad, double offset_m, double lateral_std_m) {
  const Eigen::Vector2d n(-std::sin(heading_rad), std::cos(heading_rad));
  const Eigen::Vector2d t(T_a_b_odometry.x_m, T_a_b_odometry.y_m);
  const Eigen::Vector2d measured = t + (offset_m - n.dot(t)) * n;
  const double info = 1.0 / (lateral_std_m * lateral_std_m);
  PoseGraphEdge e;
  e.from_id = a_id;
  e.to_id = b_id;
  e.kind = EdgeKind::kWall;
  e.T_from_to = {measured.x(), measured.y(), T_a_b_odometry.yaw_rad};
  const Eigen::Matrix2d across = n * n.transpose();
  e.information.setZero();
  e.information.topLeftCorner<2, 2>() =
      info * across + kWeakFraction * info * (Eigen::Matrix2d::Identity() - across);
  e.information(2, 2) = kWeakFraction * info;
  return e;
}

std::vector<PoseGraphEdge> WallEdgeFinder::Add(const Keyframe& keyframe, const cv::Mat& detected,
                                               const ImageGrid& grid) {
  if (!config_.enabled || !keyframe.complete || detected.empty()) return {};
  return Add(keyframe, KeyframeWallProfile(keyframe, detected, grid, config_));
}

std::vector<PoseGraphEdge> WallEdgeFinder::Add(const Keyframe& keyframe,
                                               const WallProfile& profile) {
  std::vector<PoseGraphEdge> edges;
  if (!config_.enabled || !keyframe.complete) return edges;
  Recent now;
  now.id = keyframe.id;
  now.T_world_anchor = keyframe.T_world_anchor;
  now.heading_rad = keyframe.T_world_robot.yaw_rad;
  now.profile = profile;
  const double max_turn_rad = config_.max_heading_change_deg * kPi / 180.0;
  // Walk back while the path stays straight: every keyframe from the earlier one up to this
  // one keeps its heading within max_turn of the earlier one's.
  double lo = 0.0, hi = 0.0;  // heading of the keyframes in between, relative to this one
  for (int back = 1; back <= static_cast<int>(recent_.size()); ++back) {
    const Recent& then = recent_[recent_.size() - static_cast<std::size_t>(back)];
    const double turn = NormalizeAngle(then.heading_rad - now.heading_rad);
    lo = std::min(lo, turn);
    hi = std::max(hi, turn);
    if (hi - lo > max_turn_rad) break;
    if (now.id - then.id > config_.max_gap) break;
    if (now.id - then.id < config_.min_gap) continue;
    // b = now, a = then: the odometry's offset of b's anchor along a's left normal.
    const Pose2 T_a_b = Between(then.T_world_anchor, now.T_world_anchor);
    const double heading_in_a = then.heading_rad - then.T_world_anchor.yaw_rad;
    const double predicted =
        -std::sin(heading_in_a) * T_a_b.x_m + std::cos(heading_in_a) * T_a_b.y_m;
    ++pairs_tried_;
    const WallProfileAlignment aligned =
        AlignWallProfiles(then.profile, now.profile, predicted, config_);
    if (!aligned.accepted) continue;
    edges.push_back(
        MakeEdge(then.id, now.id, T_a_b, heading_in_a, aligned.offset_m, config_.lateral_std_m));
  }
  recent_.push_back(std::move(now));
  while (static_cast<int>(recent_.size()) > config_.max_gap) recent_.pop_front();
  return edges;
}

}  // namespace uwbsar::slam
