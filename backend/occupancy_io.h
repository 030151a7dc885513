// Writing occupancy grids in the ROS map_server format: a trinary PGM (254 free,
// 0 occupied, 205 unknown; row 0 = top of the map) and its YAML (image, mode,
// resolution, origin [x, y, yaw], negate 0, occupied_thresh 0.65, free_thresh
// 0.196), both written atomically. free_thresh 0.196 (as ROS 1's map_saver) makes
// grey 205 read back as unknown in every map_server reader, ours
// (imaging/occupancy_grid.h) included: p(205) = 50/255 = 0.196 is not below it.
#pragma once

#include <string>

#include "imaging/occupancy_grid.h"

namespace uwbsar {

/// Writes `yaml_path` and, next to it, the image `image_name` (relative to the YAML's folder).
void WriteOccupancyGrid(const std::string& yaml_path, const std::string& image_name,
                        const OccupancyGrid& grid);

}  // namespace uwbsar
