// SE(2) poses and the few operations every layer needs. Plain struct, no
// dependency beyond <cmath>; frames are named at the call site (T_world_robot).
#pragma once

#include <cmath>

namespace uwbsar {

/// |x|, |y| in metres of any position uwbsar reads from a file (a pose, a map's or grid's
/// origin): 1000 km, where a float (PCL, images) still resolves 6 cm. Beyond, a value is damage.
inline constexpr double kMaxWorldCoordinateM = 1e6;

/// Wraps an angle to [-pi, pi).
inline double NormalizeAngle(double angle_rad) {
  constexpr double kTwoPi = 2.0 * M_PI;
  double a = std::fmod(angle_rad + M_PI, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return a - M_PI;
}

struct Point2 {
  double x_m = 0.0;
  double y_m = 0.0;
};

/// A rigid 2-D transform T_a_b: maps points in frame b to frame a.
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;

  /// T_a_c = T_a_b * T_b_c.
  Pose2 operator*(const Pose2& b_c) const {
    const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
    return {x_m + c * b_c.x_m - s * b_c.y_m, y_m + s * b_c.x_m + c * b_c.y_m,
            NormalizeAngle(yaw_rad + b_c.yaw_rad)};
  }
  /// p_a = T_a_b * p_b.
  Point2 operator*(const Point2& p_b) const {
    const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
    return {x_m + c * p_b.x_m - s * p_b.y_m, y_m + s * p_b.x_m + c * p_b.y_m};
  }
  /// T_b_a.
  Pose2 Inverse() const {
    const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
    return {-(c * x_m + s * y_m), -(-s * x_m + c * y_m), NormalizeAngle(-yaw_rad)};
  }
};

/// T_a_b given T_w_a and T_w_b (pose of b in the frame of a).
inline Pose2 Between(const Pose2& T_w_a, const Pose2& T_w_b) { return T_w_a.Inverse() * T_w_b; }

/// Euclidean distance between the positions of two poses.
inline double Distance(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
}

/// Linear interpolation of position and shortest-arc interpolation of yaw, t in [0, 1].
inline Pose2 Interpolate(const Pose2& a, const Pose2& b, double t) {
  return {a.x_m + t * (b.x_m - a.x_m), a.y_m + t * (b.y_m - a.y_m),
          NormalizeAngle(a.yaw_rad + t * NormalizeAngle(b.yaw_rad - a.yaw_rad))};
}

}  // namespace uwbsar
