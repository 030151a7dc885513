// The global map kept between renders: a live run rewrites its map every few seconds, and
// after the first lap almost every keyframe stays where it was. IncrementalMosaic remembers
// the pose each keyframe's tile was drawn at and the blocks it reached, and an update redoes
// only the blocks of keyframes that appeared, left (retired) or moved, so the cost of a render
// follows what changed, not the size of the map.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <vector>

#include "backend/global_map.h"

namespace uwbsar {

/// What an update redid.
struct MosaicUpdate {
  std::size_t added = 0;          ///< keyframes new to the map
  std::size_t removed = 0;        ///< keyframes gone from it
  std::size_t moved = 0;          ///< keyframes redrawn at a new pose
  std::size_t tiles_drawn = 0;    ///< tiles read back and drawn (into some of their blocks)
  std::size_t blocks_redone = 0;  ///< blocks cleared and drawn again
};

class IncrementalMosaic {
 public:
  /// `resolution_m`: the map's pixel; a keyframe is redrawn when some corner of its tile lies
  /// more than `redraw_px` map pixels from where it was drawn (so the map never differs
  /// from a full render by more than that shift per tile).
  IncrementalMosaic(double resolution_m, double redraw_px, int block_px = 256);

  /// Brings the map to `tiles` (every keyframe of the map, each once): the same, up to
  /// `redraw_px`, as adding all of them to a fresh GlobalMap.
  MosaicUpdate Update(const std::vector<MosaicTile>& tiles);

  const GlobalMap& map() const { return map_; }

 private:
  struct Drawn {
    Pose2 T_world_tile;  ///< the pose it was drawn at
    ImageGrid grid;
    GlobalMap::BlockSet blocks;
  };
  /// Largest shift, in metres, of the tile's corners between the two poses.
  static double CornerShiftM(const ImageGrid& grid, const Pose2& a, const Pose2& b);

  GlobalMap map_;
  double redraw_m_;
  std::map<int, Drawn> drawn_;
};

}  // namespace uwbsar
