// A SAR intensity image as an occupancy grid, so that `uwbsar compare` scores images from
// any imager (the paper's published strips, `uwbsar image` strips, `uwbsar map`'s
// map_float.tif) against a LiDAR grid. The image is described by a grid YAML (image, x0_m,
// y0_m, resolution_m; imaging/sar_grid_metadata.h) and becomes occupancy with the paper's
// intensity rule (backend/global_map.h MapToOccupancy; `uwbsar map`'s map.pgm is the navigation
// grid of backend/navigation_grid.h instead).
#pragma once

#include <string>

#include "imaging/occupancy_grid.h"

namespace uwbsar {

/// The paper's intensity rule (slam.occupancy_resolution_m, slam.occupied_fraction,
/// slam.occupancy_reference_percentile).
struct SarOccupancyRule {
  double cell_m = 0.05;
  double occupied_fraction = 0.3;
  double reference_percentile = 99.0;
};

/// The intensity rule as the configuration sets it (slam.occupancy_resolution_m,
/// slam.occupied_fraction, slam.occupancy_reference_percentile).
template <class SlamSection>
SarOccupancyRule SarOccupancyRuleOf(const SlamSection& slam) {
  return {slam.occupancy_resolution_m, slam.occupied_fraction, slam.occupancy_reference_percentile};
}

/// True when `yaml_path` is a SAR grid YAML (has `x0_m`, no `origin`) rather than a
/// map_server map. Throws InputError naming the file when it cannot be read as a mapping.
bool IsSarGridYaml(const std::string& yaml_path);

/// Reads the image the grid YAML names and applies the rule: pixels that are 0 were not
/// measured (unknown cells); 8/16-bit images are intensities as they are, float images
/// (1 page real, 2 pages re/im) become their positive image (Re + |Re|, or |I|). Throws
/// InputError naming the file on bad input.
/// Images declaring more than `max_image_pixels` are refused before decoding, and so is an
/// image whose extent (pixels x the grid's resolution_m) implies an occupancy grid of more
/// than `max_image_pixels` cells at rule.cell_m, before the grid is allocated.
OccupancyGrid SarImageToOccupancy(const std::string& grid_yaml, const SarOccupancyRule& rule,
                                  double max_image_pixels);

}  // namespace uwbsar
