#include "eval/compare/sar_image_occupancy.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "backend/global_map.h"
#include "core/errors.h"
#include "core/yaml_file.h"
#include "imaging/enhance.h"
#include "imaging/sar_image_file.h"

namespace uwbsar {
namespace {

/// The occupancy grid the image's extent implies at `cell_m` (MapToOccupancy's size), against
/// the budget, before it is allocated: a grid YAML's resolution_m sets the extent.
void CheckOccupancySize(const std::string& grid_yaml, const ImageGrid& grid, double cell_m,
                        double max_cells) {
  const double cols = std::max(1.0, std::ceil(grid.width_m() / cell_m));
  const double rows = std::max(1.0, std::ceil(grid.height_m() / cell_m));
  if (std::isfinite(cols * rows) && cols * rows <= max_cells) return;
  std::ostringstream msg;
  msg.precision(3);
  msg << grid_yaml << ": grid key 'resolution_m' (" << grid.resolution_m << " m x " << grid.cols
      << " x " << grid.rows << " pixels: " << grid.width_m() << " x " << grid.height_m()
      << " m) implies an occupancy grid of " << cols << " x " << rows
      << " cells at slam.occupancy_resolution_m " << cell_m
      << " m, more than limits.max_map_image_pixels (" << max_cells << ")";
  throw InputError(msg.str());
}

}  // namespace

bool IsSarGridYaml(const std::string& yaml_path) {
  const YAML::Node root = LoadYamlMappingFile(yaml_path, "map");
  return root["x0_m"] && !root["origin"];
}

OccupancyGrid SarImageToOccupancy(const std::string& grid_yaml, const SarOccupancyRule& rule,
                                  double max_image_pixels) {
  // The resolution comes from the grid YAML; ReadSarImageFile needs no default.
  const SarImageFile file = ReadSarImageFile(grid_yaml, 1.0, max_image_pixels);
  cv::Mat intensity;
  if (file.enhanced) {
    file.image.convertTo(intensity, CV_32F);
  } else {
    intensity = PositiveImage(file.image);
    cv::patchNaNs(intensity, 0.0);
  }
  CheckOccupancySize(grid_yaml, file.grid, rule.cell_m, max_image_pixels);
  return MapToOccupancy(intensity, file.observed, file.grid, rule.cell_m, rule.occupied_fraction,
                        rule.reference_percentile);
}

}  // namespace uwbsar
