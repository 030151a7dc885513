// Per-radar matching (radar_match.h) on corridors of SAR-like texture: a revisit in the
// opposite direction whose shared wall is seen only by the other radar, far and faint
// beside a bright near wall the first pass did not see; and a different corridor.
#include "frontend/place_recognition/radar_match.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "slam/config/system_config.h"
#include "test/frontend/place_recognition/texture.h"

namespace uwbsar {
namespace {

/// A 10 m x 4 m world of texture at 5 mm (what a radar images of the walls there).
struct Wall {
  ImageGrid grid = ImageGrid::Covering(-1.0, 9.0, -2.0, 2.0, 0.005);
  cv::Mat image;  // CV_32F, > 0 everywhere
  explicit Wall(std::uint64_t seed) {
    cv::Mat tex = testing::BlobTexture(grid.cols, seed, 4000);
    tex(cv::Rect(0, 0, grid.cols, grid.rows)).convertTo(image, CV_32F, 1.0 / 255.0, 0.01);
  }
};

/// What one radar of a keyframe imaged: `wall`, times `gain`, on the side y_sign of the path
/// (in the anchor frame, 0.3 to 2 m from it).
struct SideView {
  int sensor_id = 0;
  const Wall* wall = nullptr;
  double gain = 1.0;
  double y_sign = 1.0;
};

/// A keyframe over 2 m of path from its anchor (truly at T_world_anchor_true, told
/// T_world_anchor_odom), the robot heading `heading_rad`, with one sensor tile per view.
Keyframe CorridorTile(int id, const Pose2& T_world_anchor_true, const Pose2& T_world_anchor_odom,
                      double heading_rad, double path_begin_m, const std::vector<SideView>& views) {
  Keyframe k;
  k.id = id;
  k.grid = ImageGrid::Covering(-0.5, 2.5, -2.0, 2.0, 0.005);
  k.image = cv::Mat::zeros(k.grid.rows, k.grid.cols, CV_32F);
  k.T_world_anchor = T_world_anchor_odom;
  k.T_world_robot = {T_world_anchor_odom.x_m + 1.0, T_world_anchor_odom.y_m, heading_rad};
  k.path_begin_m = path_begin_m;
  k.path_end_m = path_begin_m + 2.0;
  k.complete = true;
  const double c = std::cos(T_world_anchor_true.yaw_rad), s = std::sin(T_world_anchor_true.yaw_rad);
  for (const SideView& v : views) {
    SensorTile st;
    st.sensor_id = v.sensor_id;
    st.grid = v.y_sign > 0 ? ImageGrid::Covering(-0.5, 2.5, 0.3, 2.0, 0.005)
                           : ImageGrid::Covering(-0.5, 2.5, -2.0, -0.3, 0.005);
    // Sensor-tile pixel -> anchor metres -> world metres -> wall pixel, as one affine map.
    const Point2 origin = T_world_anchor_true * st.grid.PixelToMetric(0, 0);
    const cv::Matx23d m(c, s, v.wall->grid.XToCol(origin.x_m), -s, c,
                        v.wall->grid.YToRow(origin.y_m));
    cv::warpAffine(v.wall->image, st.image, cv::Mat(m), cv::Size(st.grid.cols, st.grid.rows),
                   cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, cv::Scalar(0));
    st.image *= v.gain;
    const cv::Rect in_tile(static_cast<int>(std::lround(k.grid.XToCol(st.grid.x0_m))),
                           static_cast<int>(std::lround(k.grid.YToRow(st.grid.y0_m))), st.grid.cols,
                           st.grid.rows);
    cv::Mat roi = k.image(in_tile);
    roi += st.image;
    k.sensor_tiles.push_back(std::move(st));
  }
  return k;
}

const Wall& WallA() {
  static const Wall w(101);
  return w;
}
const Wall& WallB() {
  static const Wall w(202);
  return w;
}
const Wall& WallC() {
  static const Wall w(303);
  return w;
}
const Wall& WallD() {
  static const Wall w(404);
  return w;
}
const Wall& WallE() {
  static const Wall w(505);
  return w;
}
const Wall& WallF() {
  static const Wall w(606);
  return w;
}

// Radars of the default configuration: 0 looks left (+90 deg), 1 looks right (-90 deg).
constexpr int kLeft = 0;
constexpr int kRight = 1;

/// The way out along +x: the left radar sees wall A, the right radar wall B.
Keyframe WayOut() {
  const Pose2 anchor{2.0, 0.0, 0.0};
  return CorridorTile(0, anchor, anchor, 0.0, 0.0,
                      {{kLeft, &WallA(), 1.0, +1.0}, {kRight, &WallB(), 1.0, -1.0}});
}

TEST(RadarMatchTest, OppositeRevisitSeenOnlyByTheOtherRadarIsMatchedAcrossSides) {
  SystemConfig config;
  PlaceRecognizer pr(config);
  EXPECT_TRUE(pr.Process(WayOut()).attempts.empty());
  // The way back along -x, 0.4 m to the right of the way out: the right radar (looking +y
  // now) sees wall A far and faint; the left one a bright near wall C that the way out
  // did not see (another reflector), which sets the combined tile's contrast.
  const Pose2 back_true{2.15, -0.4, 0.02};
  const Pose2 back_odom{2.35, -0.25, 0.0};  // drifted
  const Keyframe back =
      CorridorTile(1, back_true, back_odom, M_PI, 40.0,
                   {{kLeft, &WallC(), 1.0, -1.0}, {kRight, &WallA(), 0.03, +1.0}});
  const PlaceRecognitionResult r = pr.Process(back);
  ASSERT_EQ(r.attempts.size(), 1u);
  const LoopAttempt& a = r.attempts[0];
  ASSERT_TRUE(a.validation.accepted) << a.validation.reason;
  EXPECT_TRUE(a.by_radar);
  EXPECT_TRUE(a.cross_side);
  ASSERT_EQ(r.loops.size(), 1u);
  const Pose2 truth = Between(Pose2{2.0, 0.0, 0.0}, back_true);
  EXPECT_NEAR(r.loops[0].T_ij.x_m, truth.x_m, 0.01);
  EXPECT_NEAR(r.loops[0].T_ij.y_m, truth.y_m, 0.01);
  EXPECT_NEAR(r.loops[0].T_ij.yaw_rad, truth.yaw_rad, 0.01);

  // Without per-radar matching the combined tiles do not match: the pass is what finds it.
  SystemConfig combined_only;
  combined_only.place_recognition.per_radar.enabled = false;
  PlaceRecognizer paper(combined_only);
  paper.Process(WayOut());
  const PlaceRecognitionResult p = paper.Process(back);
  ASSERT_EQ(p.attempts.size(), 1u);
  EXPECT_FALSE(p.attempts[0].validation.accepted);
}

TEST(RadarMatchTest, DifferentCorridorsAreNotMatched) {
  SystemConfig config;
  PlaceRecognizer pr(config);
  pr.Process(WayOut());
  // Other corridors (walls the way out never saw) at the same estimated place, driven the
  // other way and the same way.
  const Pose2 other{2.1, -0.3, 0.0};
  const PlaceRecognitionResult back = pr.Process(CorridorTile(
      1, other, other, M_PI, 40.0, {{kLeft, &WallC(), 1.0, -1.0}, {kRight, &WallD(), 0.03, +1.0}}));
  const PlaceRecognitionResult same = pr.Process(CorridorTile(
      2, other, other, 0.0, 80.0, {{kLeft, &WallE(), 1.0, +1.0}, {kRight, &WallF(), 0.2, -1.0}}));
  for (const PlaceRecognitionResult* r : {&back, &same}) {
    EXPECT_FALSE(r->attempts.empty());
    EXPECT_TRUE(r->loops.empty());
    for (const LoopAttempt& a : r->attempts) {
      EXPECT_FALSE(a.validation.accepted) << a.candidate_id << " -> " << r->keyframe_id;
    }
  }
}

TEST(RadarMatchTest, RadarsArePairedByTheirLookDirectionInTheWorld) {
  SystemConfig config;
  KeyframeFeatures out = ExtractKeyframeFeatures(WayOut(), config);
  ASSERT_TRUE(HasRadarFeatures(out, PlaceRecognitionConfig()));
  ASSERT_EQ(out.look_anchor_rad.size(), 2u);
  EXPECT_NEAR(out.look_anchor_rad[kLeft], M_PI / 2, 1e-9);
  EXPECT_NEAR(out.look_anchor_rad[kRight], -M_PI / 2, 1e-9);
  // Every keypoint lies on its radar's side of the path, in pixels of the whole tile.
  for (const FeatureSet* f :
       {&out.RadarFeatures(DetectorKind::kAkaze), &out.RadarFeatures(DetectorKind::kOrb)}) {
    EXPECT_GT(f->size(), 20);
    EXPECT_EQ(f->descriptors.rows, f->size());
    for (const cv::KeyPoint& kp : f->keypoints) {
      const double y_m = out.grid.RowToY(kp.pt.y);
      EXPECT_EQ(kp.class_id == kLeft, y_m > 0.0) << y_m;
    }
  }
  // A revisit the same way pairs each radar with itself: matched against itself, it is
  // accepted and not across sides.
  KeyframeFeatures again = out;
  again.id = 1;
  const LoopAttempt a = MatchByRadar(
      out, again, AtFeatureResolution(config.place_recognition, FeatureDownsampling(config)));
  EXPECT_TRUE(a.validation.accepted) << a.validation.reason;
  EXPECT_FALSE(a.cross_side);
}

// ExtractKeyframeFeatures computes the radars' features on a thread of their own, beside the
// combined tile's: the same features, in the same pixels, as one after the other.
TEST(RadarMatchTest, RadarFeaturesBesideTheTilesAreThoseComputedAlone) {
  SystemConfig config;
  const PlaceRecognizerConfig pr(config);
  const Keyframe keyframe = WayOut();
  const KeyframeFeatures both = ExtractKeyframeFeatures(keyframe, pr);
  KeyframeFeatures alone;
  alone.grid = keyframe.grid;
  ImageGrid tile_grid = keyframe.grid;
  const DetectorConfig& d = pr.place_recognition.detectors;
  DownsampleFeatureImage(MakeFeatureImage(keyframe.image, pr.enhance, d.mask_erode_px),
                         pr.feature_downsampling, d.white_percentile, &tile_grid);
  EXPECT_EQ(both.grid.cols, tile_grid.cols);
  EXPECT_EQ(both.grid.rows, tile_grid.rows);
  EXPECT_DOUBLE_EQ(both.grid.resolution_m, tile_grid.resolution_m);
  EXPECT_DOUBLE_EQ(both.grid.x0_m, tile_grid.x0_m);
  EXPECT_DOUBLE_EQ(both.grid.y0_m, tile_grid.y0_m);
  alone.grid = tile_grid;
  ExtractRadarFeatures(keyframe, pr, &alone);
  for (DetectorKind kind : {DetectorKind::kAkaze, DetectorKind::kOrb}) {
    const FeatureSet& a = both.RadarFeatures(kind);
    const FeatureSet& b = alone.RadarFeatures(kind);
    ASSERT_GT(a.size(), 20);
    ASSERT_EQ(a.size(), b.size());
    for (int k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a.keypoints[k].pt, b.keypoints[k].pt);
      EXPECT_EQ(a.keypoints[k].class_id, b.keypoints[k].class_id);
    }
    EXPECT_EQ(cv::norm(a.descriptors, b.descriptors, cv::NORM_INF), 0.0);
  }
}

}  // namespace
}  // namespace uwbsar
