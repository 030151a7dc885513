#include "eval/compare/pcd_export.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "core/errors.h"
#include "eval/compare/sar_peaks.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

std::string Header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text, line;
  while (std::getline(in, line) && line.rfind("DATA", 0) != 0) text += line + "\n";
  return text + line;
}

class PcdExportTest : public ::testing::TestWithParam<bool> {};

TEST_P(PcdExportTest, OccupiedCellsRoundTripThroughPclsReader) {
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const std::vector<IntensityPoint> points = OccupiedCellPoints(lidar);
  ASSERT_GT(points.size(), 500u);
  const std::string dir = testing::FreshDir(GetParam() ? "pcd_bin" : "pcd_ascii");
  const std::string path = dir + "/map.pcd";
  WritePcd(path, points, /*binary=*/GetParam());
  const std::string header = Header(path);
  EXPECT_NE(header.find("VERSION 0.7"), std::string::npos) << header;
  EXPECT_NE(header.find("FIELDS x y z intensity"), std::string::npos) << header;
  EXPECT_NE(header.find("POINTS " + std::to_string(points.size())), std::string::npos) << header;
  EXPECT_NE(header.find(GetParam() ? "DATA binary" : "DATA ascii"), std::string::npos) << header;
  const std::vector<IntensityPoint> back = ReadPcd(path);
  ASSERT_EQ(back.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_NEAR(back[i].x_m, points[i].x_m, 1e-5);
    ASSERT_NEAR(back[i].y_m, points[i].y_m, 1e-5);
    ASSERT_FLOAT_EQ(back[i].intensity, 1.0f);
  }
  // The first occupied cell in row-major order is where the grid says.
  int r0 = -1, c0 = -1;
  for (int r = 0; r < lidar.rows && r0 < 0; ++r) {
    for (int c = 0; c < lidar.cols; ++c) {
      if (lidar.IsOccupied(r, c)) {
        r0 = r;
        c0 = c;
        break;
      }
    }
  }
  EXPECT_NEAR(back[0].x_m, lidar.origin.x_m + (c0 + 0.5) * 0.05, 1e-5);
  EXPECT_NEAR(back[0].y_m, lidar.origin.y_m + (lidar.rows - r0 - 0.5) * 0.05, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(BinaryAndAscii, PcdExportTest, ::testing::Bool());

TEST(PcdExportErrorTest, UnwritablePathAndUnreadableFileAreInputErrors) {
  EXPECT_THROW(WritePcd("/nonexistent_dir/x.pcd", {{0, 0, 1}}, true), InputError);
  const std::string dir = testing::FreshDir("pcd_bad");
  std::ofstream(dir + "/junk.pcd") << "not a point cloud\n";
  EXPECT_THROW(ReadPcd(dir + "/junk.pcd"), InputError);
}

/// A float SAR map with Gaussian blobs (positive) and a negative lobe.
FloatSarMap BlobMap() {
  FloatSarMap map;
  map.grid = {-1.0, 2.0, 0.01, 100, 200, "paper", ""};
  map.image = cv::Mat(100, 200, CV_32F, cv::Scalar(0));
  auto blob = [&](int row, int col, float amplitude) {
    for (int r = 0; r < map.image.rows; ++r) {
      for (int c = 0; c < map.image.cols; ++c) {
        const double d2 = (r - row) * (r - row) + (c - col) * (c - col);
        map.image.at<float>(r, c) += amplitude * static_cast<float>(std::exp(-d2 / 8.0));
      }
    }
  };
  blob(20, 30, 1.0f);
  blob(70, 150, 0.5f);
  blob(50, 100, 0.05f);  // below 20 % of the strongest: dropped
  blob(80, 40, -2.0f);   // negative: not a scatterer in the positive image
  return map;
}

TEST(SarPeaksTest, StrongScatterersBecomePointsAtTheirWorldPosition) {
  const std::vector<IntensityPoint> peaks = SarPeaks(BlobMap(), 0.2, 0.05);
  ASSERT_EQ(peaks.size(), 2u);
  const auto strongest = std::max_element(
      peaks.begin(), peaks.end(),
      [](const IntensityPoint& a, const IntensityPoint& b) { return a.intensity < b.intensity; });
  EXPECT_NEAR(strongest->x_m, -1.0 + 30 * 0.01, 1e-9);
  EXPECT_NEAR(strongest->y_m, 2.0 - 20 * 0.01, 1e-9);
  EXPECT_NEAR(strongest->intensity, 2.0f, 1e-4);  // paper's positive image: 2 max(I, 0)
  const auto weaker = strongest == peaks.begin() ? peaks.begin() + 1 : peaks.begin();
  EXPECT_NEAR(weaker->x_m, -1.0 + 150 * 0.01, 1e-9);
  EXPECT_NEAR(weaker->y_m, 2.0 - 70 * 0.01, 1e-9);
}

TEST(SarPeaksTest, FloatTiffAndGridYamlAreReadAndCheckedAgainstEachOther) {
  const std::string dir = testing::FreshDir("peaks");
  const FloatSarMap map = BlobMap();
  ASSERT_TRUE(cv::imwrite(dir + "/strip_float.tif", map.image));
  std::ofstream(dir + "/strip_grid.yaml")
      << "x0_m: -1.0\ny0_m: 2.0\nresolution_m: 0.01\nrows: 100\ncols: 200\nmode: paper\n";
  const FloatSarMap loaded = LoadFloatSarMap(dir + "/strip_float.tif", dir + "/strip_grid.yaml");
  EXPECT_EQ(SarPeaks(loaded, 0.2, 0.05).size(), 2u);
  std::ofstream(dir + "/wrong_grid.yaml")
      << "x0_m: -1.0\ny0_m: 2.0\nresolution_m: 0.01\nrows: 99\ncols: 200\n";
  try {
    LoadFloatSarMap(dir + "/strip_float.tif", dir + "/wrong_grid.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wrong_grid.yaml"), std::string::npos) << e.what();
  }
  std::ofstream(dir + "/bad_grid.yaml") << "x0_m: 0\ny0_m: 0\nresolution_m: 0\nrows: 1\ncols: 1\n";
  EXPECT_THROW(LoadFloatSarMap(dir + "/strip_float.tif", dir + "/bad_grid.yaml"), InputError);
}

}  // namespace
}  // namespace uwbsar
