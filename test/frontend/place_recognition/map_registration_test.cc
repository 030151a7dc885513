#include "frontend/place_recognition/map_registration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "frontend/place_recognition/loop_validator.h"

namespace uwbsar {
namespace {

struct Scatterer {
  Point2 p_world;
  double amplitude = 1.0;
};

std::vector<Scatterer> RandomScene(std::uint64_t seed, int count, double x0, double x1, double y0,
                                   double y1) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1), ua(0.3, 1.0);
  std::vector<Scatterer> s;
  for (int k = 0; k < count; ++k) s.push_back({{ux(rng), uy(rng)}, ua(rng)});
  return s;
}

/// A detected tile (CV_32FC1, 1 cm) of 3 m x 4 m seen from `T_world_anchor`: each scatterer a
/// Gaussian of 2 cm on a dim floor; a 20 cm band along one side not observed (0).
cv::Mat RenderTile(const std::vector<Scatterer>& scene, const Pose2& T_world_anchor,
                   ImageGrid* grid) {
  *grid = ImageGrid::Covering(0.0, 3.0, -2.0, 2.0, 0.01);
  cv::Mat tile(grid->rows, grid->cols, CV_32FC1, cv::Scalar(0.05f));
  const Pose2 T_anchor_world = T_world_anchor.Inverse();
  for (const Scatterer& s : scene) {
    const Point2 q = T_anchor_world * s.p_world;
    const double col = grid->XToCol(q.x_m), row = grid->YToRow(q.y_m);
    for (int r = static_cast<int>(row) - 6; r <= static_cast<int>(row) + 6; ++r) {
      for (int c = static_cast<int>(col) - 6; c <= static_cast<int>(col) + 6; ++c) {
        if (r < 0 || c < 0 || r >= tile.rows || c >= tile.cols) continue;
        const double d2 = (r - row) * (r - row) + (c - col) * (c - col);
        tile.at<float>(r, c) += static_cast<float>(s.amplitude * std::exp(-d2 / (2 * 2.0 * 2.0)));
      }
    }
  }
  tile.colRange(0, 20).setTo(0.0f);  // not observed
  return tile;
}

const Pose2 kA{2.0, 1.0, 0.3};
const Pose2 kB{2.6, 1.5, 0.35};  // 0.78 m and 2.9 deg on from kA

RegistrationImage Image(const std::vector<Scatterer>& scene, const Pose2& T_world_anchor) {
  ImageGrid grid;
  const cv::Mat tile = RenderTile(scene, T_world_anchor, &grid);
  return MakeRegistrationImage(tile, grid, MapRegistrationConfig{});
}

TEST(MapRegistrationTest, PixelAndMetricTransformsAreInverse) {
  const ImageGrid a = ImageGrid::Covering(-1.0, 2.0, -1.5, 1.0, 0.02);
  const ImageGrid b = ImageGrid::Covering(0.5, 3.0, -2.0, 2.0, 0.02);
  const Pose2 T_ab{0.4, -0.3, 0.2};
  const PixelRigid p = MetricToPixelTransform(a, b, T_ab);
  const Pose2 back = PixelToMetricTransform(a, b, p.tx_px, p.ty_px, p.rotation_deg);
  EXPECT_NEAR(back.x_m, T_ab.x_m, 1e-9);
  EXPECT_NEAR(back.y_m, T_ab.y_m, 1e-9);
  EXPECT_NEAR(back.yaw_rad, T_ab.yaw_rad, 1e-12);
}

TEST(MapRegistrationTest, TheImageHasTheConfiguredPixelExactlyAndItsObservedMask) {
  const std::vector<Scatterer> scene = RandomScene(1, 300, -1, 7, -3, 6);
  ImageGrid grid;
  const cv::Mat tile = RenderTile(scene, kA, &grid);
  MapRegistrationConfig config;
  config.resolution_m = 0.02;
  const RegistrationImage r = MakeRegistrationImage(tile, grid, config);
  ASSERT_FALSE(r.empty());
  EXPECT_DOUBLE_EQ(r.grid.resolution_m, 0.02);
  EXPECT_EQ(r.grid.cols, 150);
  EXPECT_EQ(r.grid.rows, 200);
  // The pixel centres stay where the tile's are: output column c averages input 2c .. 2c+1.
  EXPECT_NEAR(r.grid.x0_m, grid.ColToX(0.5), 1e-12);
  // The unobserved band (20 tile pixels, 10 image pixels and the blur's edge) is masked.
  EXPECT_EQ(r.image.mask.at<std::uint8_t>(100, 5), 0);
  EXPECT_EQ(r.image.gray.at<std::uint8_t>(100, 5), 0);
  EXPECT_EQ(r.image.mask.at<std::uint8_t>(100, 100), 255);
  EXPECT_GE(r.image.gray.at<std::uint8_t>(100, 100), 1);
  EXPECT_TRUE(MakeRegistrationImage(cv::Mat(), grid, MapRegistrationConfig{}).empty());
}

TEST(MapRegistrationTest, FindsTheTruePoseFromAnOffPrediction) {
  const std::vector<Scatterer> scene = RandomScene(1, 300, -1, 7, -3, 6);
  const RegistrationImage a = Image(scene, kA), b = Image(scene, kB);
  const Pose2 truth = Between(kA, kB);
  const Pose2 predicted = truth * Pose2{0.06, -0.05, 1.0 * M_PI / 180};
  const MapRegistrationConfig config;
  const MapRegistration r = RegisterTiles(a, b, predicted, config);
  ASSERT_TRUE(r.accepted) << r.reason;
  const Pose2 e = Between(truth, r.T_ab);
  EXPECT_LT(std::hypot(e.x_m, e.y_m), 0.01);
  EXPECT_LT(std::abs(e.yaw_rad), 0.2 * M_PI / 180);
  EXPECT_NEAR(r.information(0, 0), 1.0 / (config.sigma_xy_m * config.sigma_xy_m), 1e-6);
}

TEST(MapRegistrationTest, HoldsWhenObjectsWereAddedAndMovedSinceTheMap) {
  const std::vector<Scatterer> day1 = RandomScene(1, 300, -1, 7, -3, 6);
  std::vector<Scatterer> day2 = day1;
  // Ten bright new objects, and a tenth of the old scatterers moved by 30-50 cm.
  for (const Scatterer& s : RandomScene(7, 10, 1, 4, 0, 4)) day2.push_back({s.p_world, 3.0});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (std::size_t k = 0; k < day2.size(); k += 10) {
    day2[k].p_world.x_m += u(rng) > 0 ? 0.4 : -0.4;
    day2[k].p_world.y_m += u(rng);
  }
  const RegistrationImage map = Image(day1, kA), now = Image(day2, kB);
  const Pose2 truth = Between(kA, kB);
  const MapRegistration r =
      RegisterTiles(map, now, truth * Pose2{-0.05, 0.04, -0.8 * M_PI / 180}, {});
  ASSERT_TRUE(r.accepted) << r.reason;
  const Pose2 e = Between(truth, r.T_ab);
  EXPECT_LT(std::hypot(e.x_m, e.y_m), 0.015);
  EXPECT_LT(std::abs(e.yaw_rad), 0.3 * M_PI / 180);
}

TEST(MapRegistrationTest, AnotherPlaceIsRefused) {
  const RegistrationImage a = Image(RandomScene(1, 300, -1, 7, -3, 6), kA);
  const RegistrationImage other = Image(RandomScene(2, 300, -1, 7, -3, 6), kB);
  const MapRegistration r = RegisterTiles(a, other, Between(kA, kB), {});
  EXPECT_FALSE(r.accepted);
  EXPECT_FALSE(r.reason.empty());
}

TEST(MapRegistrationTest, ALoneWallIsRefusedAsNotDistinct) {
  // Scatterers densely along one line only: a wall, which fits anywhere along itself.
  std::vector<Scatterer> wall;
  for (double x = -2; x < 8; x += 0.01) wall.push_back({{x, 1.2}, 1.0});
  const RegistrationImage a = Image(wall, {2.0, 1.0, 0.0}), b = Image(wall, {2.5, 1.1, 0.0});
  const MapRegistration r = RegisterTiles(a, b, Between(Pose2{2.0, 1.0, 0.0}, {2.5, 1.1, 0.0}), {});
  EXPECT_FALSE(r.accepted);
  // Along the wall the correlation is a ridge: its peak is not distinct, or it runs to the edge
  // of the window.
  EXPECT_TRUE(r.reason.find("not distinct") != std::string::npos ||
              r.reason.find("edge of the search window") != std::string::npos)
      << r.reason;
}

}  // namespace
}  // namespace uwbsar
