// Straight walls as landmarks of the pose graph (place_recognition.wall_profiles.landmarks).
//
// A landmark is a line in the world: the points p with n(normal_rad) . p = offset_m, where
// n(a) = (cos a, sin a). A keyframe that sees the wall measures the same line in its own frame
// (frontend/wall_line.h). The residual of such an observation compares the predicted line with
// the measured one where the keyframe saw the wall (its reference point q, in the node's
// frame), so that the offset and the angle errors are nearly independent:
//
//   predicted in the node's frame:  normal  a_n = a - yaw,   offset  d_n = d - n(a) . t
//   e = [ (d_n - n(a_n) . q) - (d_obs - n(a_obs) . q) ;  wrap(a_n - a_obs) ]
//   r = [ e_0 / offset_std_m ; e_1 / normal_std_rad ]
//
// with (t, yaw) the node's pose. The line (a, d) is the same as (a + pi, -d); a landmark keeps
// the orientation of its first observation, and ObservationFacing turns a later observation
// to it.
#pragma once

#include <cmath>

#include "core/pose2.h"

namespace uwbsar {

/// A line: the points p with (cos normal_rad, sin normal_rad) . p = offset_m.
struct Line2 {
  double normal_rad = 0.0;
  double offset_m = 0.0;
};

/// One keyframe's measurement of a landmark: the line in the node's frame, where it was seen,
/// and how well.
struct LineObservation {
  int landmark_id = 0;
  int node_id = 0;
  Line2 line_node;        ///< the measured line in the node's frame
  Point2 reference_node;  ///< where the keyframe saw the wall (node frame): the offset is
                          ///< compared there
  double offset_std_m = 0.02;
  double normal_std_rad = 0.017;
};

/// The world line `line_frame` (given in a frame whose pose in the world is T_world_frame).
Line2 LineToWorld(const Pose2& T_world_frame, const Line2& line_frame);
/// The frame's view of the world line `line_world`.
Line2 LineToFrame(const Pose2& T_world_frame, const Line2& line_world);
/// `line` turned to face `reference` ((a + pi, -d) when their normals differ by more than 90
/// degrees; the same line either way).
Line2 Facing(const Line2& line, const Line2& reference);
/// n . p - d: the signed distance of point `p` from `line` along its normal (same frame).
double SignedDistance(const Line2& line, const Point2& p);

/// The whitened squared residual (chi2) of `observation` for a node at T_world_node and the
/// landmark `line_world` (both in one frame).
double LineObservationChi2(const LineObservation& observation, const Pose2& T_world_node,
                           const Line2& line_world);

}  // namespace uwbsar
