#include "backend/global_map.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "backend/incremental_mosaic.h"
#include "core/errors.h"

namespace uwbsar {

GlobalMap::GlobalMap(double resolution_m, int block_px)
    : resolution_m_(resolution_m), block_px_(block_px) {}

std::size_t GlobalMap::memory_bytes() const {
  return blocks_.size() * 2u * static_cast<std::size_t>(block_px_) * block_px_ * sizeof(float);
}

void GlobalMap::BlockSpan::Include(long long bc, long long br) {
  bc0 = std::min(bc0, bc), bc1 = std::max(bc1, bc);
  br0 = std::min(br0, br), br1 = std::max(br1, br);
}

void GlobalMap::BlockSpan::Include(const BlockSpan& other) {
  if (other.empty()) return;
  Include(other.bc0, other.br0);
  Include(other.bc1, other.br1);
}

GlobalMap::BlockSet GlobalMap::BlockSpan::Keys() const {
  BlockSet keys;
  for (long long br = br0; br <= br1; ++br) {
    for (long long bc = bc0; bc <= bc1; ++bc) keys.insert({bc, br});
  }
  return keys;
}

void GlobalMap::EraseBlocks(const BlockSet& blocks) {
  for (const BlockKey& key : blocks) blocks_.erase(key);
}

// Lattice pixel (c, r) has its centre at world (c * res, -r * res); block (bc, br)
// holds lattice pixels [bc * B, bc * B + B) x [br * B, br * B + B).
GlobalMap::BlockSpan GlobalMap::TileBlocks(const ImageGrid& grid, const Pose2& T_world_tile) const {
  // World bounding box of the tile's corners.
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (double c : {-0.5, grid.cols - 0.5}) {
    for (double r : {-0.5, grid.rows - 0.5}) {
      const Point2 p = T_world_tile * grid.PixelToMetric(c, r);
      lo_x = std::min(lo_x, p.x_m), hi_x = std::max(hi_x, p.x_m);
      lo_y = std::min(lo_y, p.y_m), hi_y = std::max(hi_y, p.y_m);
    }
  }
  const auto floor_div = [](long long a, long long b) {
    return a >= 0 ? a / b : -((-a + b - 1) / b);
  };
  BlockSpan span;
  span.bc0 = floor_div(static_cast<long long>(std::floor(lo_x / resolution_m_)), block_px_);
  span.bc1 = floor_div(static_cast<long long>(std::ceil(hi_x / resolution_m_)), block_px_);
  span.br0 = floor_div(static_cast<long long>(std::floor(-hi_y / resolution_m_)), block_px_);
  span.br1 = floor_div(static_cast<long long>(std::ceil(-lo_y / resolution_m_)), block_px_);
  return span;
}

double GlobalMap::SpanPixels(const BlockSpan& span) const {
  if (span.empty()) return 0.0;
  return (static_cast<double>(span.bc1) - static_cast<double>(span.bc0) + 1.0) *
         (static_cast<double>(span.br1) - static_cast<double>(span.br0) + 1.0) *
         static_cast<double>(block_px_) * static_cast<double>(block_px_);
}

GlobalMap::BlockSpan GlobalMap::AllocatedBlocks() const {
  BlockSpan span;
  for (const auto& [key, block] : blocks_) span.Include(key.first, key.second);
  return span;
}

void GlobalMap::AddTile(const cv::Mat& tile, const ImageGrid& grid, const Pose2& T_world_tile,
                        const BlockSet* only) {
  CV_Assert(tile.type() == CV_32FC1 && tile.rows == grid.rows && tile.cols == grid.cols);
  if (tile.empty()) return;
  const BlockSpan span = TileBlocks(grid, T_world_tile);
  // Block pixel (u, v) of block (bc, br) -> world -> tile pixel: an affine map.
  const Pose2 T_tile_world = T_world_tile.Inverse();
  const double ct = std::cos(T_tile_world.yaw_rad), st = std::sin(T_tile_world.yaw_rad);
  cv::Mat observed;
  cv::compare(tile, 0.0f, observed, cv::CMP_GT);
  cv::Mat ones;
  observed.convertTo(ones, CV_32F, 1.0 / 255.0);
  for (long long br = span.br0; br <= span.br1; ++br) {
    for (long long bc = span.bc0; bc <= span.bc1; ++bc) {
      if (only && !only->count({bc, br})) continue;
      // World of block pixel (u, v): x = (bc B + u) res, y = -(br B + v) res.
      // Tile metric p = T_tile_world * world; tile pixel col = (p.x - x0) / res_t,
      // row = (y0 - p.y) / res_t.
      const double rt = grid.resolution_m, rw = resolution_m_;
      const double wx0 = static_cast<double>(bc * block_px_) * rw;
      const double wy0 = -static_cast<double>(br * block_px_) * rw;
      // p.x = ct*wx - st*wy + tx ; p.y = st*wx + ct*wy + ty, with wx = wx0 + u rw, wy = wy0 - v rw
      const double px0 = ct * wx0 - st * wy0 + T_tile_world.x_m;
      const double py0 = st * wx0 + ct * wy0 + T_tile_world.y_m;
      cv::Matx23d M((ct * rw) / rt, (st * rw) / rt, (px0 - grid.x0_m) / rt, -(st * rw) / rt,
                    (ct * rw) / rt, (grid.y0_m - py0) / rt);
      cv::Mat warped, weight;
      cv::warpAffine(tile, warped, M, cv::Size(block_px_, block_px_),
                     cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, 0.0);
      cv::warpAffine(ones, weight, M, cv::Size(block_px_, block_px_),
                     cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, 0.0);
      if (cv::countNonZero(weight) == 0) continue;
      Block& b = blocks_[{bc, br}];
      if (b.sum.empty()) {
        b.sum = cv::Mat::zeros(block_px_, block_px_, CV_32FC1);
        b.weight = cv::Mat::zeros(block_px_, block_px_, CV_32FC1);
      }
      b.sum += warped;
      b.weight += weight;
    }
  }
}

double GlobalMap::RenderPixels() const { return SpanPixels(AllocatedBlocks()); }

cv::Mat GlobalMap::Render(ImageGrid* grid) const {
  cv::Mat observed;
  return Render(grid, &observed);
}

cv::Mat GlobalMap::Render(ImageGrid* grid, cv::Mat* observed) const {
  const BlockSpan span = AllocatedBlocks();
  const long long bc0 = span.bc0, bc1 = span.bc1, br0 = span.br0, br1 = span.br1;
  grid->resolution_m = resolution_m_;
  if (blocks_.empty()) {
    grid->rows = grid->cols = 0;
    *observed = cv::Mat();
    return cv::Mat();
  }
  const double cols = static_cast<double>(bc1 - bc0 + 1) * block_px_;
  const double rows = static_cast<double>(br1 - br0 + 1) * block_px_;
  if (cols > INT_MAX || rows > INT_MAX) {
    throw std::length_error("global map: " + std::to_string(cols) + " x " + std::to_string(rows) +
                            " pixels at " + std::to_string(resolution_m_) +
                            " m is too large to render");
  }
  grid->cols = static_cast<int>(cols);
  grid->rows = static_cast<int>(rows);
  grid->x0_m = static_cast<double>(bc0 * block_px_) * resolution_m_;
  grid->y0_m = -static_cast<double>(br0 * block_px_) * resolution_m_;
  cv::Mat out = cv::Mat::zeros(grid->rows, grid->cols, CV_32FC1);
  *observed = cv::Mat::zeros(grid->rows, grid->cols, CV_8UC1);
  for (const auto& [key, block] : blocks_) {
    const cv::Rect roi(static_cast<int>((key.first - bc0) * block_px_),
                       static_cast<int>((key.second - br0) * block_px_), block_px_, block_px_);
    cv::Mat mean;
    cv::divide(block.sum, cv::max(block.weight, 1e-6), mean);
    cv::Mat seen;
    cv::compare(block.weight, 1e-3, seen, cv::CMP_GT);
    mean.setTo(0.0f, ~seen);
    mean.copyTo(out(roi));
    seen.copyTo((*observed)(roi));
  }
  return out;
}

OccupancyGrid MapToOccupancy(const cv::Mat& map, const cv::Mat& observed, const ImageGrid& grid,
                             double cell_m, double occupied_fraction, double reference_percentile) {
  OccupancyGrid occ;
  occ.resolution_m = cell_m;
  if (map.empty()) return occ;
  // Reference level: a high percentile of the observed pixels.
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(cv::countNonZero(observed)));
  for (int r = 0; r < map.rows; ++r) {
    const float* m = map.ptr<float>(r);
    const unsigned char* o = observed.ptr<unsigned char>(r);
    for (int c = 0; c < map.cols; ++c) {
      if (o[c]) values.push_back(m[c]);
    }
  }
  float reference = 0.0f;
  if (!values.empty()) {
    const std::size_t k =
        std::min(values.size() - 1, static_cast<std::size_t>(reference_percentile / 100.0 *
                                                             static_cast<double>(values.size())));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    reference = values[k];
  }
  const float threshold = static_cast<float>(occupied_fraction) * reference;
  // Cells on a lattice of cell_m: the map's left/top edge is the grid's outer border.
  const double left = grid.x0_m - 0.5 * grid.resolution_m;
  const double top = grid.y0_m + 0.5 * grid.resolution_m;
  const double cols = std::max(1.0, std::ceil(grid.width_m() / cell_m));
  const double rows = std::max(1.0, std::ceil(grid.height_m() / cell_m));
  if (!(cols * rows < static_cast<double>(INT_MAX))) {
    throw std::length_error("MapToOccupancy: an occupancy grid of " + std::to_string(cols) + " x " +
                            std::to_string(rows) + " cells (unbudgeted)");
  }
  occ.cols = static_cast<int>(cols);
  occ.rows = static_cast<int>(rows);
  occ.origin = {left, top - occ.rows * cell_m, 0.0};
  occ.cells.assign(static_cast<std::size_t>(occ.rows) * occ.cols, OccupancyGrid::kUnknown);
  std::vector<float> cell_max(occ.cells.size(), -1.0f);
  const double scale = grid.resolution_m / cell_m;
  for (int r = 0; r < map.rows; ++r) {
    const float* m = map.ptr<float>(r);
    const unsigned char* o = observed.ptr<unsigned char>(r);
    const int cr = std::min(occ.rows - 1, static_cast<int>((r + 0.5) * scale));
    for (int c = 0; c < map.cols; ++c) {
      if (!o[c]) continue;
      const int cc = std::min(occ.cols - 1, static_cast<int>((c + 0.5) * scale));
      float& v = cell_max[static_cast<std::size_t>(cr) * occ.cols + cc];
      v = std::max(v, m[c]);
    }
  }
  for (std::size_t i = 0; i < occ.cells.size(); ++i) {
    if (cell_max[i] < 0.0f) continue;
    occ.cells[i] = reference > 0.0f && cell_max[i] >= threshold ? OccupancyGrid::kOccupied
                                                                : OccupancyGrid::kFree;
  }
  return occ;
}

RenderedGlobalMap RenderGlobalMap(const std::vector<MosaicTile>& tiles, double resolution_m,
                                  double max_pixels, const std::string& what,
                                  IncrementalMosaic* mosaic) {
  std::optional<GlobalMap> fresh;
  if (mosaic) {
    mosaic->Update(tiles);
  } else {
    fresh.emplace(resolution_m);
    for (const MosaicTile& t : tiles) fresh->AddTile(t.load(), t.grid, t.T_world_tile);
  }
  const GlobalMap& global = mosaic ? mosaic->map() : *fresh;
  if (!(global.RenderPixels() <= max_pixels)) {
    std::ostringstream msg;
    msg << what << ": the map of its keyframes is " << global.RenderPixels() << " pixels at "
        << resolution_m << " m, more than limits.max_image_pixels (" << max_pixels
        << "); refused before allocation";
    throw InputError(msg.str());
  }
  RenderedGlobalMap out;
  out.map = global.Render(&out.grid, &out.observed);
  out.blocks = global.num_blocks();
  out.memory_bytes = global.memory_bytes();
  return out;
}

}  // namespace uwbsar
