// Wall-profile edges of one trajectory (place_recognition.wall_profiles): each new keyframe's
// wall profile (frontend/wall_profile.h) is aligned with those of the keyframes min_gap to
// max_gap before it on the same straight stretch, and every accepted alignment becomes an
// EdgeKind::kWall edge that fixes the sideways offset between the two anchors.
#pragma once

#include <deque>
#include <opencv2/core.hpp>
#include <vector>

#include "backend/pose_graph.h"
#include "frontend/keyframe.h"
#include "frontend/keyframe_products.h"
#include "frontend/wall_profile.h"

namespace uwbsar::slam {

class WallEdgeFinder {
 public:
  explicit WallEdgeFinder(const WallProfileConfig& config) : config_(config) {}

  /// The edges from earlier keyframes to `keyframe`, whose detected tile is `detected` on
  /// `grid` (its anchor frame). Keyframes must come in path order; a tile cut short
  /// (!keyframe.complete) is neither paired nor kept.
  std::vector<PoseGraphEdge> Add(const Keyframe& keyframe, const cv::Mat& detected,
                                 const ImageGrid& grid);
  /// The same with the tile's profile made by the caller (frontend/keyframe_products.h).
  std::vector<PoseGraphEdge> Add(const Keyframe& keyframe, const WallProfile& profile);

  int pairs_tried() const { return pairs_tried_; }

  /// The edge for a sideways offset `offset_m` of b's anchor from a's along the left normal of
  /// the heading `heading_rad` (in a's anchor frame): the odometry's T_a_b with its sideways
  /// component replaced, information 1 / lateral_std_m^2 across the path and next to nothing
  /// along it or in yaw (those stay the odometry's).
  static PoseGraphEdge MakeEdge(int a_id, int b_id, const Pose2& T_a_b_odometry, double heading_rad,
                                double offset_m, double lateral_std_m);

 private:
  struct Recent {
    int id = 0;
    Pose2 T_world_anchor;      ///< odometry
    double heading_rad = 0.0;  ///< the robot's heading in the world (odometry)
    WallProfile profile;
  };

  const WallProfileConfig config_;
  std::deque<Recent> recent_;  ///< the last max_gap complete keyframes, oldest first
  int pairs_tried_ = 0;
};

}  // namespace uwbsar::slam
