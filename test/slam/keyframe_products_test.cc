// A keyframe's products (frontend/keyframe_products.h): mapping (SlamSystem) and localisation
// (LocalizePipeline) make them by one step, so the same keyframe gives both the same detected
// tile, wall profile and wall lines (issue 46: they were made twice, in each pipeline).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "slam/app_config.h"
#include "slam/localization/localize_pipeline.h"
#include "slam/slam_system.h"
#include "slam/wall_landmarks.h"
#include "test/frontend/corridor_tile.h"

namespace uwbsar::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A map whose one keyframe saw one wall (a line landmark): localisation then reads walls.
SessionData OneWallMap() {
  SessionData map;
  SessionKeyframe k;
  k.id = 0;
  map.keyframes.push_back(k);
  const Line2 wall{kPi / 2, 1.0};
  map.landmarks.push_back({0, wall});
  SessionLineObservation o;
  o.observation.landmark_id = 0;
  o.observation.node_id = 0;
  o.observation.line_node = wall;
  o.observation.reference_node = {0.0, 1.0};
  map.line_observations.push_back(o);
  return map;
}

void ExpectSameTile(const cv::Mat& a, const cv::Mat& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.type(), b.type());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(KeyframeProductsTest, MappingAndLocalisationMakeTheSameProductsOfAKeyframe) {
  Config config;
  config.slam.keyframe_thread = false;
  config.slam.map_resolution_m = 0.02;  // the tile's 1 cm brought to the map's 2 cm
  WallProfileConfig& walls = config.place_recognition.wall_profiles;
  walls.enabled = true;
  walls.landmarks.enabled = true;
  walls.landmarks.require_calibrated_base = false;
  // A complete corridor tile, the robot heading 30 deg, walls 1.0 m left and 1.25 m right.
  Keyframe k;
  k.id = 3;
  k.complete = true;
  k.T_world_anchor = {4.0, 2.0, 0.0};
  k.T_world_robot = {4.0, 2.0, kPi / 6};
  k.grid = testing::TileGrid();
  k.image = testing::CorridorTile(k.grid, kPi / 6, {1.0, -1.25}, 7);

  const SlamSystem mapping(config);
  const SessionData map = OneWallMap();
  const LocalizePipeline localisation(map, config, "test");
  const KeyframeProducts m = mapping.Products(k);
  const KeyframeProducts l = localisation.Products(k);

  ExpectSameTile(m.detected, l.detected);
  EXPECT_EQ(m.detected.cols, k.grid.cols / 2);
  EXPECT_EQ(m.grid.resolution_m, l.grid.resolution_m);
  EXPECT_EQ(m.grid.x0_m, l.grid.x0_m);
  EXPECT_EQ(m.grid.y0_m, l.grid.y0_m);
  ASSERT_TRUE(m.wall_profile.has_value());
  ASSERT_TRUE(l.wall_profile.has_value());
  EXPECT_EQ(m.wall_profile->heading_rad, l.wall_profile->heading_rad);
  EXPECT_EQ(m.wall_profile->bins, l.wall_profile->bins);
  EXPECT_EQ(m.wall_profile->contrast, l.wall_profile->contrast);
  ASSERT_EQ(m.wall_lines.size(), 2u);  // both walls
  ASSERT_EQ(l.wall_lines.size(), m.wall_lines.size());
  for (std::size_t i = 0; i < m.wall_lines.size(); ++i) {
    EXPECT_EQ(m.wall_lines[i].normal_rad, l.wall_lines[i].normal_rad);
    EXPECT_EQ(m.wall_lines[i].offset_m, l.wall_lines[i].offset_m);
    EXPECT_EQ(m.wall_lines[i].offset_std_m, l.wall_lines[i].offset_std_m);
    EXPECT_EQ(m.wall_lines[i].begin_m, l.wall_lines[i].begin_m);
    EXPECT_EQ(m.wall_lines[i].end_m, l.wall_lines[i].end_m);
  }
  // What the landmark tracker and the map's walls read of them: the same lines.
  const std::vector<SeenLine> seen_m = SeenLines(m), seen_l = SeenLines(l);
  ASSERT_EQ(seen_m.size(), seen_l.size());
  for (std::size_t i = 0; i < seen_m.size(); ++i) {
    EXPECT_EQ(seen_m[i].line_anchor.offset_m, seen_l[i].line_anchor.offset_m);
    EXPECT_EQ(seen_m[i].reference_anchor.x_m, seen_l[i].reference_anchor.x_m);
  }
}

}  // namespace
}  // namespace uwbsar::slam
