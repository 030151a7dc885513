// Wall landmarks in the session file (format version 7, slam/session/session_landmarks.h): the
// landmarks and their observations round-trip exactly, a row that refers to no landmark or
// keyframe (or has no uncertainty) is refused naming it, a version 6 file reads with none, and
// dense renumbering follows the keyframes.
#include "slam/session/session_landmarks.h"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "slam/session/landmark_join.h"
#include "slam/session/session_file.h"
#include "test/slam/session/session_test_util.h"
#include "test/slam/session/sqlite_edit.h"
#include "test/slam/session/tiny_session.h"

namespace uwbsar {
namespace {
namespace fs = std::filesystem;
using testing::ErrorOf;

/// The tiny session with one wall seen by its three keyframes (the last one rejected).
SessionData WithWall() {
  SessionData d = testing::TinySession();
  d.landmarks.push_back({4, Line2{1.5, 0.75}});
  for (int k = 0; k < 3; ++k) {
    SessionLineObservation o;
    o.observation.landmark_id = 4;
    o.observation.node_id = k;
    o.observation.line_node = LineToFrame(d.keyframes[k].T_map_anchor, d.landmarks[0].line_map);
    o.observation.reference_node = {0.8, 0.1 * k};
    o.observation.offset_std_m = 0.02 + 0.001 * k;
    o.observation.normal_std_rad = 0.017;
    o.rejected = k == 2;
    d.line_observations.push_back(o);
  }
  return d;
}

class SessionLandmarksTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() /
            ("uwbsar_landmarks_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name()))
               .string();
    fs::create_directories(dir_);
    path_ = dir_ + "/session.uwbsar";
    WriteSession(path_, WithWall());
  }
  void TearDown() override { fs::remove_all(dir_); }
  void Sql(const std::string& sql) { ::uwbsar::testing::RunSql(path_, sql); }
  std::string dir_, path_;
};

TEST_F(SessionLandmarksTest, LandmarksAndObservationsRoundTripExactly) {
  const SessionData saved = WithWall();
  const SessionData d = ReadSession(path_);
  EXPECT_EQ(d.format_version, kSessionFormatVersion);
  ASSERT_EQ(d.landmarks.size(), 1u);
  EXPECT_EQ(d.landmarks[0].id, 4);
  EXPECT_EQ(d.landmarks[0].line_map.normal_rad, 1.5);
  EXPECT_EQ(d.landmarks[0].line_map.offset_m, 0.75);
  ASSERT_EQ(d.line_observations.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const LineObservation& a = saved.line_observations[k].observation;
    const LineObservation& b = d.line_observations[k].observation;
    EXPECT_EQ(b.landmark_id, 4);
    EXPECT_EQ(b.node_id, k);
    EXPECT_EQ(b.line_node.normal_rad, a.line_node.normal_rad);
    EXPECT_EQ(b.line_node.offset_m, a.line_node.offset_m);
    EXPECT_EQ(b.reference_node.y_m, a.reference_node.y_m);
    EXPECT_EQ(b.offset_std_m, a.offset_std_m);
    EXPECT_EQ(d.line_observations[k].rejected, k == 2);
  }
  EXPECT_EQ(d.MaxLandmarkId(), 4);
}

TEST_F(SessionLandmarksTest, ObservationsOfNothingAreRefusedNamingTheRowAndColumn) {
  Sql("UPDATE line_observations SET landmark_id = 9 WHERE idx = 1");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": line_observations row 2: landmark_id 9 is not a landmark");
  Sql("UPDATE line_observations SET landmark_id = 4, keyframe_id = 7 WHERE idx = 1");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": line_observations row 2: keyframe_id 7 is not a keyframe");
  Sql("UPDATE line_observations SET keyframe_id = 1, offset_std_m = 0 WHERE idx = 1");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": line_observations row 2: offset_std_m must be > 0");
  Sql("UPDATE line_observations SET offset_std_m = 0.02; UPDATE landmarks SET offset_m = NULL");
  EXPECT_NE(ErrorOf([&] { ReadSession(path_); }).find(path_ + ": landmarks row 1: offset_m"),
            std::string::npos);
}

TEST_F(SessionLandmarksTest, AVersion6FileHasNoLandmarks) {
  Sql("DROP TABLE line_observations; DROP TABLE landmarks; "
      "UPDATE meta SET value = '6' WHERE key = 'format_version'");
  const SessionData d = ReadSession(path_);
  EXPECT_EQ(d.format_version, 6);
  EXPECT_TRUE(d.landmarks.empty());
  EXPECT_TRUE(d.line_observations.empty());
}

TEST(SessionLandmarksDenseTest, DenseIdsFollowTheKeyframes) {
  SessionData d = WithWall();
  for (SessionKeyframe& k : d.keyframes) k.id += 10;
  for (SessionEdge& e : d.edges) e.edge.from_id += 10, e.edge.to_id += 10;
  for (SessionLoop& l : d.loops) l.query_id += 10, l.match_id += 10;
  for (SessionLineObservation& o : d.line_observations) o.observation.node_id += 10;
  const SessionData dense = WithDenseIds(d);
  ASSERT_EQ(dense.line_observations.size(), 3u);
  EXPECT_EQ(dense.line_observations[2].observation.node_id, 2);
  EXPECT_EQ(dense.landmarks[0].id, 0);
  EXPECT_EQ(dense.line_observations[0].observation.landmark_id, 0);
}

TEST(SessionLandmarksCaptureTest, TheGraphsLandmarksAreCapturedWithTheObservationsOfItsNodes) {
  const SessionData d = WithWall();
  PoseGraph g;
  for (const SessionKeyframe& k : d.keyframes) g.AddNode(k.id, k.T_map_anchor, false);
  g.FixNode(0);
  for (const SessionEdge& e : d.edges) g.AddEdge(e.edge);
  g.AddLandmark(4, d.landmarks[0].line_map);
  g.AddLandmark(5, Line2{0.0, 3.0});  // seen by nobody: not captured
  for (const SessionLineObservation& o : d.line_observations) g.AddLineObservation(o.observation);
  g.Optimize();
  SessionData out;
  CaptureLandmarks(g, &out);
  ASSERT_EQ(out.landmarks.size(), 1u);
  EXPECT_EQ(out.landmarks[0].id, 4);
  EXPECT_EQ(out.line_observations.size(), 3u);
}

/// b: the same run seen again, its map frame placed at T_mapA_mapB in a's, its landmark (id
/// 20) with the normal turned over, and a second landmark (21) `away_m` off the wall.
SessionData SeenAgain(const SessionData& a, const Pose2& T_mapA_mapB, double away_m) {
  SessionData b = a;
  for (SessionKeyframe& k : b.keyframes)
    k.id += 10, k.T_map_anchor = T_mapA_mapB.Inverse() * k.T_map_anchor;
  const Line2 wall_b = LineToFrame(T_mapA_mapB, a.landmarks[0].line_map);
  b.landmarks = {{20, Line2{NormalizeAngle(wall_b.normal_rad + M_PI), -wall_b.offset_m}},
                 {21, Line2{wall_b.normal_rad, wall_b.offset_m + away_m}}};
  b.line_observations.clear();
  for (const SessionKeyframe& k : b.keyframes) {
    for (const SessionLandmark& l : b.landmarks) {
      SessionLineObservation o;
      o.observation.landmark_id = l.id;
      o.observation.node_id = k.id;
      o.observation.line_node = LineToFrame(k.T_map_anchor, l.line_map);
      o.observation.reference_node = {0.5, 0.0};
      b.line_observations.push_back(o);
    }
  }
  return b;
}

TEST(SessionLandmarksReuseTest, ASavedWallSeenAgainIsTheSameLandmarkAndAnotherWallIsNot) {
  const SessionData a = WithWall();
  const Pose2 T_mapA_mapB{2.0, -1.0, 0.4};
  SessionData b = SeenAgain(a, T_mapA_mapB, 0.3);
  const WallLineConfig config;
  EXPECT_EQ(ReuseSavedWalls(a, T_mapA_mapB, config, 4.0, &b), 1);
  ASSERT_EQ(b.landmarks.size(), 1u);
  EXPECT_EQ(b.landmarks[0].id, 21);  // 30 cm off the saved wall: another wall
  int reused = 0;
  for (const SessionLineObservation& o : b.line_observations) {
    if (o.observation.landmark_id != 4) continue;
    ++reused;
    // Turned to face the saved landmark: in a's frame it is that line.
    const Pose2 T_mapA_node = T_mapA_mapB * b.Find(o.observation.node_id)->T_map_anchor;
    const Line2 seen = LineToWorld(T_mapA_node, o.observation.line_node);
    EXPECT_NEAR(NormalizeAngle(seen.normal_rad - a.landmarks[0].line_map.normal_rad), 0.0, 1e-9);
    EXPECT_NEAR(seen.offset_m, a.landmarks[0].line_map.offset_m, 1e-9);
  }
  EXPECT_EQ(reused, 3);
  // Placed 20 cm off, the same wall is not taken for the saved one; nor one too far along it.
  SessionData off = SeenAgain(a, T_mapA_mapB, 0.3);
  EXPECT_EQ(ReuseSavedWalls(a, T_mapA_mapB * Pose2{0.0, 0.2, 0.0}, config, 4.0, &off), 0);
  SessionData far = SeenAgain(a, T_mapA_mapB, 0.3);
  EXPECT_EQ(ReuseSavedWalls(a, T_mapA_mapB, config, 0.0, &far), 0);
}

}  // namespace
}  // namespace uwbsar
