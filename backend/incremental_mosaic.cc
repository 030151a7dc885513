#include "backend/incremental_mosaic.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

namespace uwbsar {

IncrementalMosaic::IncrementalMosaic(double resolution_m, double redraw_px, int block_px)
    : map_(resolution_m, block_px), redraw_m_(redraw_px * resolution_m) {}

double IncrementalMosaic::CornerShiftM(const ImageGrid& grid, const Pose2& a, const Pose2& b) {
  double shift_m = 0.0;
  for (double c : {-0.5, grid.cols - 0.5}) {
    for (double r : {-0.5, grid.rows - 0.5}) {
      const Point2 p = grid.PixelToMetric(c, r);
      const Point2 pa = a * p, pb = b * p;
      shift_m = std::max(shift_m, std::hypot(pa.x_m - pb.x_m, pa.y_m - pb.y_m));
    }
  }
  return shift_m;
}

MosaicUpdate IncrementalMosaic::Update(const std::vector<MosaicTile>& tiles) {
  MosaicUpdate update;
  // Blocks to clear: those of keyframes that left, and the old and new blocks of those that
  // moved. A new keyframe only adds to its blocks.
  GlobalMap::BlockSet dirty;
  std::map<int, const MosaicTile*> wanted;
  for (const MosaicTile& t : tiles) wanted[t.id] = &t;
  for (auto it = drawn_.begin(); it != drawn_.end();) {
    if (wanted.count(it->first)) {
      ++it;
      continue;
    }
    dirty.insert(it->second.blocks.begin(), it->second.blocks.end());
    ++update.removed;
    it = drawn_.erase(it);
  }
  enum class State { kKept, kNew, kMoved };
  std::vector<State> state(tiles.size(), State::kKept);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const MosaicTile& t = tiles[i];
    const GlobalMap::BlockSet blocks = map_.TileBlocks(t.grid, t.T_world_tile).Keys();
    auto it = drawn_.find(t.id);
    if (it == drawn_.end()) {
      state[i] = State::kNew;
      ++update.added;
    } else if (it->second.grid.rows != t.grid.rows || it->second.grid.cols != t.grid.cols ||
               CornerShiftM(t.grid, it->second.T_world_tile, t.T_world_tile) > redraw_m_) {
      state[i] = State::kMoved;
      ++update.moved;
      dirty.insert(it->second.blocks.begin(), it->second.blocks.end());
      dirty.insert(blocks.begin(), blocks.end());
    } else {
      continue;  // drawn where it is
    }
    drawn_[t.id] = {t.T_world_tile, t.grid, blocks};
  }
  map_.EraseBlocks(dirty);
  update.blocks_redone = dirty.size();
  // New and moved keyframes are drawn whole; a kept one only into the cleared blocks it
  // reaches, at the pose it was drawn at.
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const MosaicTile& t = tiles[i];
    const Drawn& d = drawn_.at(t.id);
    GlobalMap::BlockSet only;
    if (state[i] == State::kKept) {
      std::set_intersection(d.blocks.begin(), d.blocks.end(), dirty.begin(), dirty.end(),
                            std::inserter(only, only.end()));
      if (only.empty()) continue;
    }
    const cv::Mat tile = t.load();
    map_.AddTile(tile, d.grid, d.T_world_tile, state[i] == State::kKept ? &only : nullptr);
    ++update.tiles_drawn;
  }
  return update;
}

}  // namespace uwbsar
