#include "eval/compare/map_loading.h"

#include <cmath>

namespace uwbsar {

OccupancyGrid LoadMapForComparison(const std::string& yaml_path, bool grey_205_unknown,
                                   double max_image_pixels) {
  MapPixels pixels;
  OccupancyGrid grid = LoadOccupancyGrid(yaml_path, max_image_pixels, &pixels);
  if (!grey_205_unknown) return grid;
  const MapMetadata m = LoadMapMetadata(yaml_path);
  if (m.mode != "trinary" || m.negate) return grid;
  // map_saver's unknown grey, 205 of 255, on the normalised value: the same cells in 8 and
  // 16 bits and for any PGM maxval (205 * 257 of 65535 is exactly 205 of 255).
  for (std::size_t i = 0; i < pixels.grey.size() && i < grid.cells.size(); ++i) {
    const double v = pixels.grey[i];
    if (!std::isnan(v) && std::lround(v / pixels.max_value * 255.0) == 205) {
      grid.cells[i] = OccupancyGrid::kUnknown;
    }
  }
  return grid;
}

}  // namespace uwbsar
