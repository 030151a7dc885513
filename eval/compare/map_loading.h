// Loading map_server maps for comparison, where "not observed" must stay unknown.
//
// Every common writer (ROS 1 map_saver, Nav2 map_saver, slam_toolbox, this project's
// backend/occupancy_io) marks unknown cells with grey 205 in a trinary PGM, but Nav2-style
// YAMLs say free_thresh 0.25, under which a literal map_server reader turns 205
// (occupancy 0.196) into FREE. The seed_lab LiDAR grid is such a file. Scoring those cells
// as free would score the unobserved area, so comparison reads grey 205 as unknown.
#pragma once

#include <string>

#include "imaging/occupancy_grid.h"

namespace uwbsar {

/// LoadOccupancyGrid (InputError on bad input), then, when `grey_205_unknown` is set and the
/// map is trinary and not negated, every cell whose normalised grey value is 205 of 255
/// (8 bit: exactly 205; 16 bit or another PGM maxval: the same fraction, rounded to 8 bit)
/// becomes unknown. Map images declaring more than `max_image_pixels` are refused before
/// decoding.
OccupancyGrid LoadMapForComparison(const std::string& yaml_path, bool grey_205_unknown,
                                   double max_image_pixels = LimitsConfig{}.max_map_image_pixels);

}  // namespace uwbsar
