// The global SAR map as a sparse canvas: square blocks on a world-aligned pixel
// lattice, allocated only where some tile lands, so memory follows the observed
// area and not the bounding box of the run. The fast mosaic places each
// keyframe's detected tile (positive / magnitude image, blurred; non-negative)
// at its optimised pose and averages where tiles overlap. Dense images are only
// made when rendering outputs, at any resolution.
#pragma once

#include <climits>
#include <cstddef>
#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "imaging/image_grid.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar {

class GlobalMap {
 public:
  /// `resolution_m`: pixel size of the canvas; `block_px`: block side in pixels.
  explicit GlobalMap(double resolution_m, int block_px = 256);

  using BlockKey = std::pair<long long, long long>;  ///< (block column, block row)
  using BlockSet = std::set<BlockKey>;

  /// Adds a non-negative CV_32FC1 tile whose pixels live on `grid` in the frame
  /// T_world_tile (bilinear resampling). Pixels that are exactly 0 count as unobserved.
  /// With `only`, the tile is added to those blocks alone (IncrementalMosaic redoes a few).
  void AddTile(const cv::Mat& tile, const ImageGrid& grid, const Pose2& T_world_tile,
               const BlockSet* only = nullptr);
  /// Forgets `blocks` (their sums and weights), as if no tile had reached them.
  void EraseBlocks(const BlockSet& blocks);

  /// Dense mean image over the bounding box of the allocated blocks (CV_32FC1;
  /// unobserved pixels are 0), and its grid in the world frame.
  cv::Mat Render(ImageGrid* grid) const;
  /// The same, with a mask of observed pixels (CV_8UC1, 255 = observed).
  cv::Mat Render(ImageGrid* grid, cv::Mat* observed) const;

  /// A rectangle of blocks of the lattice (block columns and rows, inclusive); empty as made.
  struct BlockSpan {
    long long bc0 = LLONG_MAX, bc1 = LLONG_MIN, br0 = LLONG_MAX, br1 = LLONG_MIN;
    bool empty() const { return bc0 > bc1; }
    void Include(long long bc, long long br);
    void Include(const BlockSpan& other);
    /// The blocks of the rectangle, as keys.
    BlockSet Keys() const;
  };
  /// The blocks a tile on `grid` at T_world_tile reaches (those AddTile visits), computed
  /// without adding it: a caller can budget a whole mosaic before making it.
  BlockSpan TileBlocks(const ImageGrid& grid, const Pose2& T_world_tile) const;
  /// Pixels (rows x cols) of the dense image over `span`, in doubles (never wrapped).
  double SpanPixels(const BlockSpan& span) const;

  /// Pixels of the dense image Render would allocate (SpanPixels of the allocated blocks),
  /// computed without allocating: a caller checks it against limits.max_image_pixels first,
  /// naming its input. Render itself throws std::length_error for an image whose side does not
  /// fit an int.
  double RenderPixels() const;

  double resolution_m() const { return resolution_m_; }
  int block_px() const { return block_px_; }
  std::size_t num_blocks() const { return blocks_.size(); }
  /// Bytes held by the blocks (sum and weight planes).
  std::size_t memory_bytes() const;

 private:
  struct Block {
    cv::Mat sum;     ///< CV_32FC1
    cv::Mat weight;  ///< CV_32FC1: number of tiles that observed the pixel
  };
  BlockSpan AllocatedBlocks() const;

  double resolution_m_;
  int block_px_;
  std::map<BlockKey, Block> blocks_;  // ordered: deterministic iteration
};

/// Occupancy from a rendered map: a cell (of `cell_m`) is unknown where no map pixel in
/// it was observed; otherwise occupied when the cell's strongest pixel reaches
/// `occupied_fraction` of the map's `reference_percentile` value (robust to a few
/// very bright scatterers), else free. The grid has ceil(extent / cell_m) cells a side: callers
/// budget that size first (it follows from the inputs); one that cannot be indexed with int
/// throws std::length_error rather than wrapping.
OccupancyGrid MapToOccupancy(const cv::Mat& map, const cv::Mat& observed, const ImageGrid& grid,
                             double cell_m, double occupied_fraction, double reference_percentile);

/// One keyframe's tile for a mosaic: `load` reads the tile back (CV_32FC1 on `grid`,
/// non-negative) and is called only when the tile must be drawn.
struct MosaicTile {
  int id = 0;
  Pose2 T_world_tile;
  ImageGrid grid;
  std::function<cv::Mat()> load;
};

class IncrementalMosaic;

/// The global map of a run's keyframes, rendered (the map of `uwbsar map`'s outputs and of a
/// live snapshot).
struct RenderedGlobalMap {
  cv::Mat map;       ///< CV_32FC1 on `grid`
  cv::Mat observed;  ///< non-zero where some tile landed
  ImageGrid grid;
  std::size_t blocks = 0;        ///< the canvas's allocated blocks
  std::size_t memory_bytes = 0;  ///< and their memory
};

/// Assembles and renders the global map of `tiles`: `mosaic` brought up to date when given (only
/// what changed since its last update is redrawn), else a map drawn from every tile at
/// `resolution_m`. A map that would pass `max_pixels` (a keyframe placed kilometres away by a
/// wild odometry jump) is refused before it is allocated: InputError naming `what`.
RenderedGlobalMap RenderGlobalMap(const std::vector<MosaicTile>& tiles, double resolution_m,
                                  double max_pixels, const std::string& what,
                                  IncrementalMosaic* mosaic = nullptr);

}  // namespace uwbsar
