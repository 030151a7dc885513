// A 2-D occupancy grid and the ROS map_server reader (YAML + PGM/PNG image).
// Conventions (shared with the map_server writer in backend/): cells are stored
// row-major with row 0 = the TOP row of the image (largest y), like the image
// file itself; `origin` is the world pose of the bottom-left corner of the
// bottom-left cell (map_server's `origin: [x, y, yaw]`). Cell values follow
// nav_msgs/OccupancyGrid: 0 free .. 100 occupied, -1 unknown.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/limits_config.h"
#include "core/pose2.h"

namespace uwbsar {

struct OccupancyGrid {
  static constexpr std::int8_t kUnknown = -1;
  static constexpr std::int8_t kFree = 0;
  static constexpr std::int8_t kOccupied = 100;
  /// Cells with a value >= this count as occupied (map_server's 0.65 default, in percent).
  static constexpr std::int8_t kOccupiedMinValue = 65;

  int rows = 0;
  int cols = 0;
  double resolution_m = 0.05;      ///< cell size
  Pose2 origin;                    ///< world pose of the bottom-left corner of the bottom-left cell
  std::vector<std::int8_t> cells;  ///< rows * cols values, row 0 = top

  bool InBounds(int row, int col) const { return row >= 0 && col >= 0 && row < rows && col < cols; }
  std::int8_t At(int row, int col) const {
    return cells[static_cast<std::size_t>(row) * cols + col];
  }
  bool IsOccupied(int row, int col) const { return At(row, col) >= kOccupiedMinValue; }
  bool IsFree(int row, int col) const {
    const std::int8_t v = At(row, col);
    return v >= 0 && v < kOccupiedMinValue;
  }

  /// World position of the centre of cell (row, col).
  Point2 CellCenter(int row, int col) const {
    return origin * Point2{(col + 0.5) * resolution_m, (rows - row - 0.5) * resolution_m};
  }
  /// Continuous cell coordinates of a world point: the cell holding it is
  /// (floor(row), floor(col)); (0, 0) is the top-left corner of the top-left cell.
  void WorldToCell(const Point2& p_world, double* row, double* col) const {
    const Point2 p = origin.Inverse() * p_world;
    *col = p.x_m / resolution_m;
    *row = rows - p.y_m / resolution_m;
  }
  /// The cell holding a world point; false if it lies outside the grid.
  bool CellOf(const Point2& p_world, int* row, int* col) const;
};

/// The cells of `grid` in nav_msgs/OccupancyGrid order: row-major starting at the
/// origin cell (the bottom row first), where uwbsar's grid stores the top row first.
std::vector<std::int8_t> GridCellsBottomUp(const OccupancyGrid& grid);

/// map_server YAML keys (ROS 1 map_server and Nav2 map_io semantics).
struct MapMetadata {
  std::string image_path;        ///< resolved against the YAML file's folder
  std::string mode = "trinary";  ///< trinary, scale or raw
  double resolution_m = 0.0;
  Pose2 origin;
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.25;
};

/// Reads a map_server map: the YAML, then its image (PGM P2/P5, or any 8/16-bit
/// grey or colour image OpenCV reads). Throws InputError naming the file, line
/// and key on a missing/unreadable image, bad PGM header or size, resolution <= 0,
/// bad thresholds, unknown mode or malformed origin.
/// PGM samples are scaled by the header's maxval (any 1..65535), so thresholds apply to the
/// same normalised value in 8 and 16 bits. `pixels` (optional) receives the grey values.
/// An image declaring more than `max_image_pixels` (limits.max_map_image_pixels) is refused
/// from its header, before it is decoded.
struct MapPixels {
  std::vector<double> grey;  ///< per cell, row 0 = top; NaN = transparent
  double max_value = 255.0;  ///< the value of white (PGM maxval, else 255 or 65535)
};
OccupancyGrid LoadOccupancyGrid(const std::string& yaml_path,
                                double max_image_pixels = LimitsConfig{}.max_map_image_pixels,
                                MapPixels* pixels = nullptr);
/// The YAML part only (no image is read).
MapMetadata LoadMapMetadata(const std::string& yaml_path);
/// Converts grey pixel values (0..max_value, row 0 = top) to cell values as map_server does:
/// occ = negate ? v / max : (max - v) / max; trinary/scale thresholds; raw keeps the value.
std::vector<std::int8_t> PixelsToCells(const std::vector<double>& pixels, double max_value,
                                       const MapMetadata& metadata);

}  // namespace uwbsar
