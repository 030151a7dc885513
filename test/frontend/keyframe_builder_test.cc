// KeyframeBuilder: a tile of two segments is the exact sum of the two one-segment
// tiles a builder with tile_length_m = tile_spacing_m makes from the same scans,
// placed on the world lattice; tiles overlap by one segment; the last is incomplete.
#include "frontend/keyframe_builder.h"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "slam/app_config.h"

namespace uwbsar {
namespace {

constexpr double kPixelM = 0.02;

/// Direct back-projection: these tests check the tiling, on synthetic profiles without the
/// quadrature ffbp needs (FfbpTest checks that ffbp's tiles are direct's).
ImagingConfig Imaging(const std::string& mode) {
  ImagingConfig imaging;
  imaging.method = ImagingMethod::kDirect;
  EXPECT_TRUE(EnumFromName(mode, &imaging.mode)) << mode;
  imaging.pixel_size_m = kPixelM;
  imaging.num_threads = 1;
  return imaging;
}

std::vector<SensorGeometry> Sensors() {
  std::vector<SensorGeometry> sensors;
  for (const RadarConfig& radar : Config{}.radars) {
    sensors.push_back(SensorGeometry::FromConfig(radar, PulseConfig{}));
  }
  return sensors;
}

/// A profile with structure over range (so misplaced pixels show), real or analytic.
std::shared_ptr<const RangeProfile> Profile(bool coherent, int scan) {
  auto p = std::make_shared<RangeProfile>();
  p->range_start_m = 0.3;
  p->range_step_m = 0.01;
  for (int k = 0; k < 300; ++k) {
    p->real.push_back(static_cast<float>(1.0 + std::sin(0.3 * k + 0.1 * scan)));
    if (coherent) p->imag.push_back(static_cast<float>(std::cos(0.2 * k)));
    p->quadrature.push_back(static_cast<float>(std::cos(0.3 * k + 0.1 * scan)));  // for ffbp
  }
  p->max_valid_range_m = p->range_start_m + 299 * p->range_step_m;
  return p;
}

/// 2.6 m of a gently curving path, one scan every 2 cm alternating between the radars.
std::vector<ImagedScan> Scans(bool coherent) {
  std::vector<ImagedScan> scans;
  Pose2 pose{0.13, -0.41, 0.3};
  double path_m = 0.0;
  for (int i = 0; i < 130; ++i) {
    ImagedScan s;
    s.stamp_ns = 1000000000LL + i * 20000000LL;
    s.sensor_id = i % 2;
    s.T_world_robot = pose;
    s.path_m = path_m;
    s.profile = Profile(coherent, i);
    scans.push_back(s);
    pose = pose * Pose2{0.02, 0.0, 0.004};
    path_m += 0.02;
  }
  return scans;
}

std::vector<Keyframe> Build(double tile_length_m, const std::string& mode,
                            bool keep_sensor_images = false,
                            const ImagingConfig* imaging = nullptr) {
  KeyframeConfig keyframe;
  keyframe.tile_length_m = tile_length_m;
  keyframe.tile_spacing_m = 1.0;
  KeyframeBuilder builder(keyframe, imaging != nullptr ? *imaging : Imaging(mode), PulseConfig{},
                          Sensors(), keep_sensor_images);
  for (const ImagedScan& s : Scans(mode == "coherent")) builder.Add(s);
  builder.Finish();
  return builder.TakeClosed();
}

/// Global lattice column and row of a tile's pixel (0, 0).
void LatticeOrigin(const Keyframe& k, long long* col0, long long* row0) {
  *col0 = std::llround((k.T_world_anchor.x_m + k.grid.x0_m) / kPixelM);
  *row0 = -std::llround((k.T_world_anchor.y_m + k.grid.y0_m) / kPixelM);
}

/// The tiles summed on one world-lattice canvas covering `extent`.
cv::Mat OnLattice(const std::vector<const Keyframe*>& tiles,
                  const std::vector<const Keyframe*>& extent) {
  long long c_lo = LLONG_MAX, r_lo = LLONG_MAX, c_hi = LLONG_MIN, r_hi = LLONG_MIN;
  for (const Keyframe* k : extent) {
    long long c0, r0;
    LatticeOrigin(*k, &c0, &r0);
    c_lo = std::min(c_lo, c0), r_lo = std::min(r_lo, r0);
    c_hi = std::max(c_hi, c0 + k->grid.cols), r_hi = std::max(r_hi, r0 + k->grid.rows);
  }
  cv::Mat canvas = cv::Mat::zeros(static_cast<int>(r_hi - r_lo), static_cast<int>(c_hi - c_lo),
                                  tiles.front()->image.type());
  for (const Keyframe* k : tiles) {
    long long c0, r0;
    LatticeOrigin(*k, &c0, &r0);
    cv::Mat roi = canvas(cv::Rect(static_cast<int>(c0 - c_lo), static_cast<int>(r0 - r_lo),
                                  k->grid.cols, k->grid.rows));
    roi += k->image;
  }
  return canvas;
}

class KeyframeBuilderTest : public ::testing::TestWithParam<std::string> {};

TEST_P(KeyframeBuilderTest, ATileIsTheSumOfItsTwoSegments) {
  const std::vector<Keyframe> tiles = Build(2.0, GetParam());
  const std::vector<Keyframe> segments = Build(1.0, GetParam());
  ASSERT_EQ(tiles.size(), 2u);
  ASSERT_EQ(segments.size(), 3u);
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const Keyframe& a = segments[t];
    const Keyframe& b = segments[t + 1];
    const std::vector<const Keyframe*> all = {&tiles[t], &a, &b};
    const cv::Mat tile = OnLattice({&tiles[t]}, all);
    const cv::Mat sum = OnLattice({&a, &b}, all);
    const double peak = cv::norm(sum, cv::NORM_INF);
    ASSERT_GT(peak, 0.0);
    EXPECT_LE(cv::norm(tile, sum, cv::NORM_INF), 1e-6 * peak) << "tile " << t;
    // Each segment alone differs from the tile: the sum is not trivially one of them.
    EXPECT_GT(cv::norm(tile, OnLattice({&a}, all), cv::NORM_INF), 0.1 * peak);
    EXPECT_EQ(tiles[t].scans.size(), a.scans.size() + b.scans.size());
    EXPECT_DOUBLE_EQ(tiles[t].path_begin_m, a.path_begin_m);
    EXPECT_DOUBLE_EQ(tiles[t].path_end_m, b.path_end_m);
  }
}

TEST_P(KeyframeBuilderTest, FfbpTilesCoverDirectsEvenWithNothingPendingWhenASegmentCloses) {
  // One scan per sub-aperture and no merge levels: each scan is written into its segment's
  // canvas as it comes, so nothing is pending when the segment closes. What it wrote must
  // still count as the segment's (its tile's pixels, and the canvas area zeroed for reuse).
  ImagingConfig ffbp = Imaging(GetParam());
  ffbp.method = ImagingMethod::kFfbp;
  ffbp.ffbp.base_scans = 1;
  ffbp.ffbp.levels = 0;
  const std::vector<Keyframe> direct = Build(2.0, GetParam());
  for (bool keep_sensor_images : {false, true}) {
    const std::vector<Keyframe> fast = Build(2.0, GetParam(), keep_sensor_images, &ffbp);
    ASSERT_EQ(fast.size(), direct.size());
    for (std::size_t t = 0; t < fast.size(); ++t) {
      EXPECT_EQ(fast[t].grid.cols, direct[t].grid.cols) << "tile " << t;
      EXPECT_EQ(fast[t].grid.rows, direct[t].grid.rows) << "tile " << t;
      EXPECT_DOUBLE_EQ(fast[t].grid.x0_m, direct[t].grid.x0_m) << "tile " << t;
      EXPECT_DOUBLE_EQ(fast[t].grid.y0_m, direct[t].grid.y0_m) << "tile " << t;
      EXPECT_GT(cv::norm(fast[t].image, cv::NORM_INF), 0.0) << "tile " << t;
    }
  }
}

TEST_P(KeyframeBuilderTest, ConsecutiveTilesShareASegmentAndOnlyTheLastIsIncomplete) {
  const std::vector<Keyframe> tiles = Build(2.0, GetParam());
  ASSERT_EQ(tiles.size(), 2u);
  EXPECT_TRUE(tiles[0].complete);
  EXPECT_FALSE(tiles[1].complete);  // 1.6 m of path, less than tile_length_m
  EXPECT_EQ(tiles[0].id, 0);
  EXPECT_EQ(tiles[1].id, 1);
  EXPECT_NEAR(tiles[1].path_begin_m, 1.0, 0.02);
  EXPECT_EQ(tiles[0].coherent(), GetParam() == "coherent");
}

TEST_P(KeyframeBuilderTest, TheAnchorIsTheLatticePointNearestTheMidPathRobot) {
  for (const Keyframe& k : Build(2.0, GetParam())) {
    EXPECT_DOUBLE_EQ(k.T_world_anchor.yaw_rad, 0.0);
    EXPECT_NEAR(k.T_world_anchor.x_m, k.T_world_robot.x_m, 0.5 * kPixelM + 1e-12);
    EXPECT_NEAR(k.T_world_anchor.y_m, k.T_world_robot.y_m, 0.5 * kPixelM + 1e-12);
    EXPECT_NEAR(std::remainder(k.T_world_anchor.x_m, kPixelM), 0.0, 1e-9);
    const double mid_path_m = 0.5 * (k.path_begin_m + k.path_end_m);
    const ImagedScan* mid = nullptr;
    for (const ImagedScan& s : k.scans) {
      if (!mid || std::abs(s.path_m - mid_path_m) < std::abs(mid->path_m - mid_path_m)) mid = &s;
    }
    ASSERT_NE(mid, nullptr);
    EXPECT_EQ(k.stamp_ns, mid->stamp_ns);
  }
}

TEST_P(KeyframeBuilderTest, SensorTilesSplitTheTileByRadar) {
  const std::vector<Keyframe> plain = Build(2.0, GetParam());
  const std::vector<Keyframe> tiles = Build(2.0, GetParam(), /*keep_sensor_images=*/true);
  ASSERT_EQ(tiles.size(), plain.size());
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const Keyframe& k = tiles[t];
    EXPECT_TRUE(plain[t].sensor_tiles.empty());
    ASSERT_EQ(k.sensor_tiles.size(), 2u);
    const double peak = cv::norm(k.image, cv::NORM_INF);
    ASSERT_GT(peak, 0.0);
    // The same tile as without sensor tiles (up to the order of the float sums) ...
    ASSERT_EQ(k.image.size(), plain[t].image.size());
    EXPECT_LE(cv::norm(k.image, plain[t].image, cv::NORM_INF), 1e-5 * peak);
    // ... and exactly the sum of its sensor tiles, each a part of the tile's lattice.
    cv::Mat sum = cv::Mat::zeros(k.image.size(), k.image.type());
    for (std::size_t s = 0; s < k.sensor_tiles.size(); ++s) {
      const SensorTile& st = k.sensor_tiles[s];
      EXPECT_EQ(st.sensor_id, static_cast<int>(s));
      EXPECT_DOUBLE_EQ(st.grid.resolution_m, k.grid.resolution_m);
      const double col = k.grid.XToCol(st.grid.x0_m), row = k.grid.YToRow(st.grid.y0_m);
      ASSERT_NEAR(col, std::round(col), 1e-6);
      ASSERT_NEAR(row, std::round(row), 1e-6);
      const cv::Rect in_tile(static_cast<int>(std::lround(col)), static_cast<int>(std::lround(row)),
                             st.grid.cols, st.grid.rows);
      ASSERT_EQ(in_tile & cv::Rect(0, 0, k.grid.cols, k.grid.rows), in_tile);
      ASSERT_EQ(st.image.size(), in_tile.size());
      cv::Mat roi = sum(in_tile);
      roi += st.image;
      // Each radar imaged something, and only its own side: a part of the tile.
      EXPECT_GT(cv::norm(st.image, cv::NORM_INF), 0.1 * peak);
      EXPECT_LT(in_tile.area(), k.grid.cols * k.grid.rows);
    }
    EXPECT_LE(cv::norm(k.image, sum, cv::NORM_INF), 1e-6 * peak) << "tile " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, KeyframeBuilderTest, ::testing::Values("paper", "coherent"));

}  // namespace
}  // namespace uwbsar
