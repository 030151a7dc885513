#include "backend/compare/sar_image_occupancy.h"

#include "backend/global_map.h"
#include "imaging/enhance.h"
#include "imaging/sar_image_file.h"
#include "slam/yaml_file.h"

namespace uwbsar {

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
  return MapToOccupancy(intensity, file.observed, file.grid, rule.cell_m, rule.occupied_fraction,
                        rule.reference_percentile);
}

}  // namespace uwbsar
