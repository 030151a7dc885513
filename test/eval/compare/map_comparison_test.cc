#include "eval/compare/map_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/errors.h"
#include "eval/compare/overlay.h"
#include "test/shared_data.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = M_PI / 180.0;

/// Runs CompareMapFiles and returns the InputError message ("" if none was thrown).
std::string CompareError(const std::string& sar, const std::string& lidar,
                         const AlignRequest& request = {}) {
  try {
    CompareMapFiles(sar, lidar, request, CompareConfig{});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(MapComparisonTest, SeedLabAgainstItselfScoresPerfectAndWritesOutputs) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string yaml = testing::SeedLabYaml();
  const ComparisonReport r = CompareMapFiles(yaml, yaml, AlignRequest{}, CompareConfig{});
  ASSERT_TRUE(r.alignment.accepted) << r.alignment.reason;
  const MapMetrics& m = r.comparison.metrics;
  EXPECT_EQ(m.differing_cells, 0);
  EXPECT_EQ(m.f1, 1.0);
  EXPECT_EQ(m.iou, 1.0);
  EXPECT_LT(m.sar_to_lidar.max_m, 1e-4);
  EXPECT_LT(m.lidar_to_sar.max_m, 1e-4);

  const std::string dir = testing::FreshDir("self");
  const auto files = WriteComparisonOutputs(r, dir, CompareConfig{});
  ASSERT_EQ(files.size(), 2u);
  const cv::Mat overlay = cv::imread(dir + "/overlay.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(overlay.empty());
  // A perfect match draws occupied cells in the "both" colour and none in "LiDAR only".
  int both = 0, lidar_only = 0;
  for (int row = 0; row < overlay.rows; ++row) {
    for (int col = 0; col < overlay.cols; ++col) {
      both += overlay.at<cv::Vec3b>(row, col) == OverlayColors::Both();
      lidar_only += overlay.at<cv::Vec3b>(row, col) == OverlayColors::LidarOnly();
    }
  }
  EXPECT_GT(both, 1000);
  EXPECT_LT(lidar_only, 200);  // only the legend swatch
  std::ifstream in(dir + "/metrics.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["metrics"]["difference_ratio"].get<double>(), 0.0);
  EXPECT_EQ(j["metrics"]["f1"].get<double>(), 1.0);
  EXPECT_EQ(j["cells"]["evaluated"].get<long long>(), m.evaluated_cells);
  EXPECT_EQ(j["alignment"]["mode"], "icp");
  EXPECT_TRUE(j["alignment"]["accepted"].get<bool>());
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(MapComparisonTest, MovedCopyAtCoarserResolutionIsRealignedThroughFiles) {
  UWBSAR_NEED_SEED_LAB_MAP();
  // The acceptance case through the files: shifted (0.4, -0.25) m, rotated 7 deg, and stored at
  // 0.1 m cells, so resampling is exercised too.
  const std::string dir = testing::FreshDir("moved");
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const Pose2 moved{0.4, -0.25, 7.0 * kDeg};
  const OccupancyGrid copy = testing::RasterizedCopy(lidar, moved, 0.1);
  const std::string copy_yaml = testing::WriteMapServer(copy, dir, "copy");
  const ComparisonReport r =
      CompareMapFiles(copy_yaml, testing::SeedLabYaml(), AlignRequest{}, CompareConfig{});
  ASSERT_TRUE(r.alignment.accepted) << r.alignment.reason;
  const Pose2 expected = moved.Inverse();
  const Pose2& T = r.alignment.T_target_source;
  EXPECT_LT(std::hypot(T.x_m - expected.x_m, T.y_m - expected.y_m), 0.05);
  EXPECT_LT(std::abs(NormalizeAngle(T.yaw_rad - expected.yaw_rad)), 0.5 * kDeg);
  EXPECT_GT(r.comparison.metrics.f1, 0.99);
  // "origin" trusts the frames as they are: the same copy scores badly.
  AlignRequest origin;
  origin.mode = "origin";
  const ComparisonReport raw = CompareMapFiles(copy_yaml, testing::SeedLabYaml(), origin, {});
  EXPECT_LT(raw.comparison.metrics.f1, 0.5);
}

TEST(MapComparisonTest, FixedTransformIsUsedAsGiven) {
  UWBSAR_NEED_SEED_LAB_MAP();
  AlignRequest fixed;
  fixed.mode = "fixed";
  fixed.T_lidar_sar = {0.05, 0.0, 0.0};  // one cell
  const std::string yaml = testing::SeedLabYaml();
  const ComparisonReport r = CompareMapFiles(yaml, yaml, fixed, CompareConfig{});
  EXPECT_DOUBLE_EQ(r.alignment.T_target_source.x_m, 0.05);
  EXPECT_GT(r.comparison.metrics.differing_cells, 0);
  EXPECT_EQ(r.comparison.metrics.f1, 1.0);
}

class BadInputTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::FreshDir("bad"); }
  std::string Yaml(const std::string& name, const std::string& image, double resolution = 0.05) {
    const std::string path = dir_ + "/" + name;
    WriteText(path, "image: " + image + "\nresolution: " + std::to_string(resolution) +
                        "\norigin: [0, 0, 0]\nnegate: 0\n");
    return path;
  }
  std::string dir_;
};

TEST_F(BadInputTest, YamlPointingToMissingImageNamesBothFiles) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string yaml = Yaml("missing.yaml", "nowhere.pgm");
  const std::string msg = CompareError(yaml, testing::SeedLabYaml());
  EXPECT_NE(msg.find("missing.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("nowhere.pgm"), std::string::npos) << msg;
}

TEST_F(BadInputTest, PgmWithWrongHeaderIsNamed) {
  UWBSAR_NEED_SEED_LAB_MAP();
  WriteText(dir_ + "/bad.pgm", "P6\n2 2\n255\n" + std::string(12, '\0'));
  const std::string msg = CompareError(testing::SeedLabYaml(), Yaml("bad.yaml", "bad.pgm"));
  EXPECT_NE(msg.find("bad.pgm"), std::string::npos) << msg;
  EXPECT_NE(msg.find("header"), std::string::npos) << msg;
}

TEST_F(BadInputTest, PgmShorterThanItsHeaderIsNamed) {
  UWBSAR_NEED_SEED_LAB_MAP();
  WriteText(dir_ + "/short.pgm", "P5\n100 100\n255\n" + std::string(50, '\xfe'));
  const std::string msg = CompareError(Yaml("short.yaml", "short.pgm"), testing::SeedLabYaml());
  EXPECT_NE(msg.find("short.pgm"), std::string::npos) << msg;
  EXPECT_NE(msg.find("size"), std::string::npos) << msg;
}

TEST_F(BadInputTest, NonPositiveResolutionIsNamed) {
  UWBSAR_NEED_SEED_LAB_MAP();
  WriteText(dir_ + "/ok.pgm", "P5\n2 2\n255\n" + std::string(4, '\xfe'));
  for (double resolution : {0.0, -0.05}) {
    const std::string msg =
        CompareError(Yaml("zero.yaml", "ok.pgm", resolution), testing::SeedLabYaml());
    EXPECT_NE(msg.find("zero.yaml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("resolution"), std::string::npos) << msg;
  }
}

TEST_F(BadInputTest, MapsThatDoNotOverlapAreRefusedInEveryAlignMode) {
  UWBSAR_NEED_SEED_LAB_MAP();
  OccupancyGrid far = testing::SeedLabGrid();
  far.origin.x_m += 100.0;
  const std::string far_yaml = testing::WriteMapServer(far, dir_, "far");
  for (const char* mode : {"icp", "origin", "fixed"}) {
    AlignRequest request;
    request.mode = mode;
    const std::string msg = CompareError(far_yaml, testing::SeedLabYaml(), request);
    EXPECT_NE(msg.find("do not overlap"), std::string::npos) << mode << ": " << msg;
    EXPECT_NE(msg.find("far.yaml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("my_map.yaml"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace uwbsar

namespace uwbsar {
namespace {

// A SAR wall one cell in front of the LiDAR's, nothing seen behind it (the radar sees a wall's
// face): the overlay drew it all red "SAR only" beside a "LiDAR (not evaluated)" line, and
// nothing said why. The key now says what each colour means and the legend why.
TEST(MapComparisonTest, OverlayLegendExplainsASarOnlyWallBesideAnUnscoredLidarLine) {
  OccupancyGrid lidar = testing::FreeGrid(40, 40, 0.05);
  OccupancyGrid sar = testing::FreeGrid(40, 40, 0.05);
  for (int r = 0; r < 40; ++r) {
    lidar.cells[static_cast<std::size_t>(r) * 40 + 30] = OccupancyGrid::kOccupied;
    sar.cells[static_cast<std::size_t>(r) * 40 + 29] = OccupancyGrid::kOccupied;
    for (int c = 30; c < 40; ++c) sar.cells[static_cast<std::size_t>(r) * 40 + c] = -1;
  }
  ComparisonReport report;
  report.lidar = lidar;
  report.sar = sar;
  report.comparison = CompareOnLidarGrid(sar, lidar, Pose2{}, 1);
  const cv::Mat overlay = RenderOverlay(report, 4);
  int sar_only = 0, lidar_unscored = 0;
  for (int row = 0; row < overlay.rows; ++row) {
    for (int col = 0; col < overlay.cols; ++col) {
      sar_only += overlay.at<cv::Vec3b>(row, col) == OverlayColors::SarOnly();
      lidar_unscored += overlay.at<cv::Vec3b>(row, col) == OverlayColors::LidarContext();
    }
  }
  EXPECT_GT(sar_only, 40 * 16 / 2);  // the wall, beside the unscored LiDAR line
  EXPECT_GT(lidar_unscored, 40 * 16 / 2);
  auto of = [](const cv::Vec3b& colour) {
    for (const auto& [c, text] : OverlayKey()) {
      if (c == colour) return text;
    }
    return std::string();
  };
  EXPECT_EQ(of(OverlayColors::SarOnly()), "SAR only (LiDAR free)");
  EXPECT_EQ(of(OverlayColors::LidarContext()), "LiDAR the radar did not see (not scored)");
  const std::vector<std::string> note = OverlayScoringNote(1);
  std::string joined;
  for (const std::string& line : note) joined += line + " ";
  EXPECT_NE(joined.find("Scored: the cells both maps know"), std::string::npos) << joined;
  EXPECT_NE(joined.find("SAR only beside an unscored LiDAR line"), std::string::npos) << joined;
  EXPECT_NE(joined.find("allow 1 cell)"), std::string::npos) << joined;
}

}  // namespace
}  // namespace uwbsar
