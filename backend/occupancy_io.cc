#include "backend/occupancy_io.h"

#include <filesystem>
#include <opencv2/core.hpp>
#include <sstream>

#include "imaging/image_io.h"

namespace uwbsar {

void WriteOccupancyGrid(const std::string& yaml_path, const std::string& image_name,
                        const OccupancyGrid& grid) {
  cv::Mat image(std::max(grid.rows, 1), std::max(grid.cols, 1), CV_8UC1, cv::Scalar(205));
  for (int r = 0; r < grid.rows; ++r) {
    unsigned char* row = image.ptr<unsigned char>(r);
    for (int c = 0; c < grid.cols; ++c) {
      const std::int8_t v = grid.At(r, c);
      row[c] = v < 0 ? 205 : (v >= OccupancyGrid::kOccupiedMinValue ? 0 : 254);
    }
  }
  const std::filesystem::path folder = std::filesystem::path(yaml_path).parent_path();
  WriteImageAtomic((folder / image_name).string(), image);
  std::ostringstream yaml;
  yaml.precision(12);
  yaml << "image: " << image_name << "\n"
       << "mode: trinary\n"
       << "resolution: " << grid.resolution_m << "\n"
       << "origin: [" << grid.origin.x_m << ", " << grid.origin.y_m << ", " << grid.origin.yaw_rad
       << "]\n"
       << "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  WriteTextAtomic(yaml_path, yaml.str());
}

}  // namespace uwbsar
