#include "backend/line_landmark.h"

#include <array>

#include "backend/line_observation_cost.h"

namespace uwbsar {

Line2 LineToWorld(const Pose2& T_world_frame, const Line2& line_frame) {
  // n_w = R n_f; a point p_f on the line maps to p_w = R p_f + t: n_w . p_w = d_f + n_w . t.
  const double a = NormalizeAngle(line_frame.normal_rad + T_world_frame.yaw_rad);
  return {a,
          line_frame.offset_m + std::cos(a) * T_world_frame.x_m + std::sin(a) * T_world_frame.y_m};
}

Line2 LineToFrame(const Pose2& T_world_frame, const Line2& line_world) {
  const double a = line_world.normal_rad;
  return {
      NormalizeAngle(a - T_world_frame.yaw_rad),
      line_world.offset_m - (std::cos(a) * T_world_frame.x_m + std::sin(a) * T_world_frame.y_m)};
}

Line2 Facing(const Line2& line, const Line2& reference) {
  if (std::abs(NormalizeAngle(line.normal_rad - reference.normal_rad)) <= 0.5 * M_PI) return line;
  return {NormalizeAngle(line.normal_rad + M_PI), -line.offset_m};
}

double SignedDistance(const Line2& line, const Point2& p) {
  return std::cos(line.normal_rad) * p.x_m + std::sin(line.normal_rad) * p.y_m - line.offset_m;
}

double LineObservationChi2(const LineObservation& observation, const Pose2& T_world_node,
                           const Line2& line_world) {
  const std::array<double, 3> pose{T_world_node.x_m, T_world_node.y_m, T_world_node.yaw_rad};
  const std::array<double, 2> landmark{line_world.normal_rad, line_world.offset_m};
  std::array<double, 2> r{};
  const LineObservationCost cost(observation);
  cost(pose.data(), landmark.data(), r.data());
  return r[0] * r[0] + r[1] * r[1];
}

}  // namespace uwbsar
