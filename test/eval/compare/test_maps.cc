#include "test_maps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "eval/compare/map_loading.h"
#include "test/shared_data.h"

namespace uwbsar::testing {

std::string SeedLabYaml() { return ::uwbsar::testing::SeedLabLidarMap(); }

OccupancyGrid SeedLabGrid() { return LoadMapForComparison(SeedLabYaml(), true); }

OccupancyGrid RasterizedCopy(const OccupancyGrid& grid, const Pose2& T, double resolution_m) {
  const double res = resolution_m > 0 ? resolution_m : grid.resolution_m;
  const int samples = static_cast<int>(std::ceil(res / grid.resolution_m - 1e-9));
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  const double w = grid.cols * grid.resolution_m, h = grid.rows * grid.resolution_m;
  for (const Point2& corner : {Point2{0, 0}, Point2{w, 0}, Point2{0, h}, Point2{w, h}}) {
    const Point2 p = T * (grid.origin * corner);
    x0 = std::min(x0, p.x_m);
    x1 = std::max(x1, p.x_m);
    y0 = std::min(y0, p.y_m);
    y1 = std::max(y1, p.y_m);
  }
  OccupancyGrid out;
  out.resolution_m = res;
  out.origin = {x0, y0, 0.0};
  out.cols = static_cast<int>(std::ceil((x1 - x0) / res));
  out.rows = static_cast<int>(std::ceil((y1 - y0) / res));
  out.cells.assign(static_cast<std::size_t>(out.rows) * out.cols, OccupancyGrid::kUnknown);
  const Pose2 T_inv = T.Inverse();
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) {
      std::int8_t& cell = out.cells[static_cast<std::size_t>(r) * out.cols + c];
      const Point2 centre = out.CellCenter(r, c);
      for (int i = 0; i < samples; ++i) {
        for (int j = 0; j < samples; ++j) {
          const Point2 p{centre.x_m + ((i + 0.5) / samples - 0.5) * res,
                         centre.y_m + ((j + 0.5) / samples - 0.5) * res};
          int sr = 0, sc = 0;
          if (grid.CellOf(T_inv * p, &sr, &sc)) cell = std::max(cell, grid.At(sr, sc));
        }
      }
    }
  }
  return out;
}

OccupancyGrid FreeGrid(int rows, int cols, double resolution_m, const Pose2& origin) {
  OccupancyGrid g;
  g.rows = rows;
  g.cols = cols;
  g.resolution_m = resolution_m;
  g.origin = origin;
  g.cells.assign(static_cast<std::size_t>(rows) * cols, OccupancyGrid::kFree);
  return g;
}

std::string WriteMapServer(const OccupancyGrid& grid, const std::string& dir,
                           const std::string& name) {
  std::ofstream pgm(dir + "/" + name + ".pgm", std::ios::binary);
  pgm << "P5\n" << grid.cols << " " << grid.rows << "\n255\n";
  for (std::int8_t v : grid.cells) {
    const char byte = v == OccupancyGrid::kUnknown            ? static_cast<char>(205)
                      : v >= OccupancyGrid::kOccupiedMinValue ? static_cast<char>(0)
                                                              : static_cast<char>(254);
    pgm.put(byte);
  }
  const std::string yaml = dir + "/" + name + ".yaml";
  std::ofstream out(yaml);
  out.precision(12);
  out << "image: " << name << ".pgm\nmode: trinary\nresolution: " << grid.resolution_m
      << "\norigin: [" << grid.origin.x_m << ", " << grid.origin.y_m << ", " << grid.origin.yaw_rad
      << "]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\n";
  return yaml;
}

std::string FreshDir(const std::string& name) {
  // One folder per test: ctest runs test cases of one suite in parallel processes.
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string unique = test != nullptr
                                 ? std::string(test->test_suite_name()) + "." + test->name()
                                 : std::string("none");
  const auto dir =
      std::filesystem::temp_directory_path() / ("uwbsar_compare_" + name + "_" + unique);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace uwbsar::testing
