// Point clouds in PCD v0.7 (PCL's format, opened by PCL and CloudCompare): fields
// x y z intensity (float), z = 0, in the map's world frame.
#pragma once

#include <string>
#include <vector>

#include "imaging/occupancy_grid.h"

namespace uwbsar {

struct IntensityPoint {
  double x_m = 0.0;
  double y_m = 0.0;
  float intensity = 0.0f;
};

/// The centres of the occupied cells; intensity = cell value / 100 (1 for trinary maps).
std::vector<IntensityPoint> OccupiedCellPoints(const OccupancyGrid& grid);

/// Writes `points` with PCL (binary or ASCII) under a temporary name, then renames.
/// Throws InputError naming the path when it cannot be written.
void WritePcd(const std::string& path, const std::vector<IntensityPoint>& points, bool binary);

/// Reads a PCD file with PCL's reader (x, y, intensity; 0 if the file has no intensity).
/// Throws InputError naming the path on a missing or malformed file.
std::vector<IntensityPoint> ReadPcd(const std::string& path);

}  // namespace uwbsar
