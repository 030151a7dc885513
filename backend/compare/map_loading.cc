#include "backend/compare/map_loading.h"

#include <opencv2/imgcodecs.hpp>

namespace uwbsar {

OccupancyGrid LoadMapForComparison(const std::string& yaml_path, bool grey_205_unknown,
                                   double max_image_pixels) {
  OccupancyGrid grid = LoadOccupancyGrid(yaml_path, max_image_pixels);
  if (!grey_205_unknown) return grid;
  const MapMetadata m = LoadMapMetadata(yaml_path);
  if (m.mode != "trinary" || m.negate) return grid;
  // The image was decoded and checked by LoadOccupancyGrid; read its grey values again.
  const cv::Mat image = cv::imread(m.image_path, cv::IMREAD_UNCHANGED);
  if (image.type() != CV_8UC1 || image.rows != grid.rows || image.cols != grid.cols) return grid;
  for (int r = 0; r < image.rows; ++r) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(r);
    for (int c = 0; c < image.cols; ++c) {
      if (row[c] == 205)
        grid.cells[static_cast<std::size_t>(r) * grid.cols + c] = OccupancyGrid::kUnknown;
    }
  }
  return grid;
}

}  // namespace uwbsar
