#include "frontend/place_recognition/place_recognizer.h"

#include <gtest/gtest.h>

#include <limits>

#include "slam/app_config.h"
#include "test/frontend/place_recognition/texture.h"

namespace uwbsar {
namespace {

/// A world of SAR-like texture, 8 m x 4 m at 5 mm, and tiles cut from it at known poses.
struct World {
  ImageGrid grid = ImageGrid::Covering(-1.0, 7.0, -2.0, 2.0, 0.005);
  cv::Mat image;  // CV_32F
  World() {
    cv::Mat tex = testing::BlobTexture(grid.cols, 77, 2500);
    tex = tex(cv::Rect(0, 0, grid.cols, grid.rows)).clone();
    tex.convertTo(image, CV_32F, 1.0 / 255.0);
  }

  /// A keyframe whose anchor truly sits at T_world_anchor_true; its odometry pose is
  /// T_world_anchor_odom (what the recognizer is told).
  Keyframe Tile(int id, const Pose2& T_world_anchor_true, const Pose2& T_world_anchor_odom,
                double path_begin_m) const {
    Keyframe k;
    k.id = id;
    k.grid = ImageGrid::Covering(-0.5, 2.5, -1.2, 1.2, 0.005);
    // tile pixel -> anchor metres -> world metres -> world pixel, as one affine map.
    const double c = std::cos(T_world_anchor_true.yaw_rad),
                 s = std::sin(T_world_anchor_true.yaw_rad);
    // Rows grow towards -y in both images, hence the signs.
    cv::Matx23d m;
    m(0, 0) = c;
    m(0, 1) = s;
    m(1, 0) = -s;
    m(1, 1) = c;
    const Point2 origin = T_world_anchor_true * k.grid.PixelToMetric(0, 0);
    m(0, 2) = grid.XToCol(origin.x_m);
    m(1, 2) = grid.YToRow(origin.y_m);
    cv::warpAffine(image, k.image, cv::Mat(m), cv::Size(k.grid.cols, k.grid.rows),
                   cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, cv::Scalar(0));
    k.T_world_anchor = T_world_anchor_odom;
    k.T_world_robot = T_world_anchor_odom;
    k.path_begin_m = path_begin_m;
    k.path_end_m = path_begin_m + 2.0;
    k.complete = true;
    return k;
  }
};

const World& TheWorld() {
  static const World world;
  return world;
}

TEST(PlaceRecognizerTest, FindsTheRevisitWithTheExactMetricTransform) {
  const World& w = TheWorld();
  Config config;
  PlaceRecognizer pr(config);
  const Pose2 first{1.0, -0.3, 0.0};
  const Pose2 revisit_true{1.15, -0.25, 0.06};
  const Pose2 revisit_odom{1.35, -0.1, 0.03};  // drifted
  EXPECT_TRUE(pr.Process(w.Tile(0, first, first, 0.0)).attempts.empty());
  const PlaceRecognitionResult r = pr.Process(w.Tile(1, revisit_true, revisit_odom, 20.0));
  ASSERT_EQ(r.candidates.ids.size(), 1u);
  ASSERT_EQ(r.loops.size(), 1u) << r.attempts.at(0).validation.reason;
  const LoopConstraint& lc = r.loops[0];
  EXPECT_EQ(lc.i, 0);
  EXPECT_EQ(lc.j, 1);
  const Pose2 truth = Between(first, revisit_true);
  EXPECT_NEAR(lc.T_ij.x_m, truth.x_m, 0.005);
  EXPECT_NEAR(lc.T_ij.y_m, truth.y_m, 0.005);
  EXPECT_NEAR(lc.T_ij.yaw_rad, truth.yaw_rad, 0.005);
  EXPECT_GT(lc.information(0, 0), 0.0);
  EXPECT_GT(r.features_ms, 0.0);
  ASSERT_NE(pr.Find(1), nullptr);
  EXPECT_GT(pr.Find(1)->Features(DetectorKind::kAkaze).size(), 10);
}

TEST(PlaceRecognizerTest, FarPriorFindsNothingButTheNoPriorModeDoes) {
  const World& w = TheWorld();
  Config config;
  const Pose2 first{1.0, -0.3, 0.0};
  const Pose2 lost{40.0, 30.0, 0.0};                              // odometry after large drift
  config.place_recognition.candidates.global_search_every_m = 0;  // no re-localisation
  PlaceRecognizer with_prior(config);
  with_prior.Process(w.Tile(0, first, first, 0.0));
  EXPECT_TRUE(with_prior.Process(w.Tile(1, first, lost, 20.0)).candidates.ids.empty());
  config.place_recognition.candidates.use_pose_prior = false;
  PlaceRecognizer relocalise(config);
  relocalise.Process(w.Tile(0, first, first, 0.0));
  EXPECT_EQ(relocalise.Process(w.Tile(1, first, lost, 20.0)).loops.size(), 1u);
}

TEST(PlaceRecognizerTest, AfterALoopDroughtOneKeyframePerIntervalIsMatchedAgainstAll) {
  const World& w = TheWorld();
  Config config;  // global_search_after_m 20, global_search_every_m 5
  const Pose2 first{1.0, -0.3, 0.0};
  const Pose2 lost{40.0, 30.0, 0.0};  // odometry after large drift
  PlaceRecognizer pr(config);
  pr.Process(w.Tile(0, first, first, 0.0));
  // 10 m after the last loop (none yet): the prior holds, the far estimate finds nothing.
  EXPECT_TRUE(pr.Process(w.Tile(1, first, lost, 10.0)).candidates.ids.empty());
  // 20 m: no prior for this keyframe; it re-localises.
  const PlaceRecognitionResult found = pr.Process(w.Tile(2, first, lost, 20.0));
  EXPECT_FALSE(found.candidates.used_prior);
  EXPECT_GE(found.loops.size(), 1u);
}

TEST(PlaceRecognizerTest, RecentKeyframesAreNeverCandidates) {
  const World& w = TheWorld();
  PlaceRecognizer pr{Config{}};
  const Pose2 p{1.0, -0.3, 0.0};
  pr.Process(w.Tile(0, p, p, 0.0));
  EXPECT_TRUE(pr.Process(w.Tile(1, p, p, 1.0)).candidates.ids.empty());  // shares scans
}

TEST(PlaceRecognizerTest, UpdatePoseMovesAKeyframeInTheIndex) {
  const World& w = TheWorld();
  PlaceRecognizer pr{Config{}};
  const Pose2 p{1.0, -0.3, 0.0};
  pr.Process(w.Tile(0, p, Pose2{30.0, 0.0, 0.0}, 0.0));  // odometry far off
  pr.UpdatePose(0, p);                                   // corrected by the backend
  EXPECT_EQ(pr.Process(w.Tile(1, p, p, 20.0)).loops.size(), 1u);
}

// Bad tiles are rejected with a reason, never a crash or a NaN constraint.
TEST(PlaceRecognizerTest, BadTilesAreRejectedWithReasons) {
  const World& w = TheWorld();
  const Pose2 p{1.0, -0.3, 0.0};
  PlaceRecognizer pr{Config{}};
  pr.Process(w.Tile(0, p, p, 0.0));
  auto expect_rejected = [&](Keyframe k, const char* what) {
    const PlaceRecognitionResult r = pr.Process(k);
    SCOPED_TRACE(what);
    EXPECT_TRUE(r.loops.empty());
    for (const LoopAttempt& a : r.attempts) {
      EXPECT_FALSE(a.validation.accepted);
      EXPECT_FALSE(a.validation.reason.empty());
      EXPECT_TRUE(a.validation.constraint.information.allFinite());
    }
  };
  Keyframe empty = w.Tile(10, p, p, 20.0);
  empty.image = cv::Mat();
  expect_rejected(empty, "empty image");
  Keyframe uniform = w.Tile(11, p, p, 30.0);
  uniform.image.setTo(0.5);
  expect_rejected(uniform, "uniform image");
  Keyframe zeros = w.Tile(12, p, p, 40.0);
  zeros.image.setTo(0.0);
  expect_rejected(zeros, "never imaged");
  Keyframe few = w.Tile(13, p, p, 50.0);
  few.image.setTo(0.0);
  cv::circle(few.image, {300, 240}, 8, cv::Scalar(1.0), cv::FILLED);  // one blob only
  expect_rejected(few, "fewer than the minimum keypoints");
  Keyframe line = w.Tile(14, p, p, 60.0);
  line.image.setTo(0.0);
  cv::line(line.image, {50, 240}, {550, 240}, cv::Scalar(1.0), 3);  // a lone wall
  expect_rejected(line, "collinear structure");
  Keyframe nan = w.Tile(15, p, p, 70.0);
  nan.image.setTo(std::numeric_limits<float>::quiet_NaN());
  expect_rejected(nan, "NaN image");
  // The database still works after all that.
  EXPECT_EQ(pr.Process(w.Tile(16, p, p, 80.0)).loops.size(), 1u);
}

}  // namespace
}  // namespace uwbsar
