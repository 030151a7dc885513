// A keyframe: an overlapping SAR tile over L metres of path, with everything
// needed to relate it metrically to other tiles and to re-render it from
// corrected poses: id, odometry pose of the anchor, tile image, imaged scans with their poses.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "core/types.h"
#include "imaging/image_grid.h"
#include "imaging/range_profile.h"

namespace uwbsar {

/// A scan that passed gating, with the odometry pose it was imaged at.
struct ImagedScan {
  TimestampNs stamp_ns = 0;
  int sensor_id = 0;
  Pose2 T_world_robot;                          ///< odometry pose at the scan's timestamp
  double path_m = 0.0;                          ///< odometry path length at the scan's timestamp
  std::shared_ptr<const RangeProfile> profile;  ///< shared by the tiles that hold the scan
};

/// One radar's part of a tile: the pixels its scans imaged, on the tile's lattice.
struct SensorTile {
  int sensor_id = 0;
  ImageGrid grid;  ///< in the tile's anchor frame: a sub-rectangle of Keyframe::grid
  cv::Mat image;   ///< same type as Keyframe::image; the tile is the sum of its sensor tiles
};

/// Tiles are imaged on one world-aligned pixel lattice (see KeyframeBuilder), so
/// the anchor frame has the world frame's orientation: T_world_anchor has yaw 0 in
/// odometry and sits on a lattice point next to the robot's position at the middle
/// of the tile's path. It is rigidly attached to the robot at that instant
/// (T_anchor_robot is constant), so a pose-graph correction of the anchor applies
/// to every scan of the tile.
struct Keyframe {
  int id = 0;
  TimestampNs stamp_ns = 0;  ///< time of the scan at the middle of the tile's path
  Pose2 T_world_anchor;      ///< odometry pose of the tile frame (see above)
  Pose2 T_world_robot;       ///< odometry pose of the robot at stamp_ns
  ImageGrid grid;            ///< pixel geometry in the anchor frame
  cv::Mat image;             ///< CV_32FC1 (paper mode) or CV_32FC2 (coherent), grid-sized
  double path_begin_m = 0.0;
  double path_end_m = 0.0;
  bool complete = false;  ///< false for the last tiles of a run, cut short
  std::vector<ImagedScan> scans;
  /// Per radar (place_recognition.per_radar): kept only when the builder was asked to;
  /// dropped with `image` once the keyframe's features are computed.
  std::vector<SensorTile> sensor_tiles;

  bool coherent() const { return image.type() == CV_32FC2; }
};

}  // namespace uwbsar
