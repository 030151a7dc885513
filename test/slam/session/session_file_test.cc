// The session file (point 1): a mapped run saved and read back is the same run
// (poses, tiles bit-exact, features, edges, loops, odometry); foreign, damaged, other-version
// and incompatible-configuration files are refused with one line.
#include "slam/session/session_file.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/errors.h"
#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/outputs/session_capture.h"
#include "slam/session/blob_codec.h"
#include "test/shared_data.h"
#include "test/slam/session/session_test_util.h"
#include "test/slam/session/version3_loops.h"

namespace uwbsar {
namespace {
namespace fs = std::filesystem;
using testing::ErrorOf;

/// A compact tile (session.lossless_tiles: false) read back: every pixel within one level
/// (max / 1023) of what was mapped (half a level above half a level), and the observed pixels
/// (> 0) exactly those.
void ExpectCompactTile(const cv::Mat& mapped, const cv::Mat& read, const std::string& what) {
  ASSERT_EQ(read.type(), CV_32FC1) << what;
  ASSERT_EQ(read.size(), mapped.size()) << what;
  double max_value = 0.0;
  cv::minMaxLoc(mapped, nullptr, &max_value);
  cv::Mat error;
  cv::absdiff(mapped, read, error);
  double max_error = 0.0;
  cv::minMaxLoc(error, nullptr, &max_error);
  EXPECT_LE(max_error, 1.0001 * max_value / session::kTileLevels) << what;
  cv::Mat above_half_level = mapped >= 0.5 * max_value / session::kTileLevels;
  double max_error_above = 0.0;
  cv::minMaxLoc(error, nullptr, &max_error_above, nullptr, nullptr, above_half_level);
  EXPECT_LE(max_error_above, 0.5001 * max_value / session::kTileLevels) << what;
  EXPECT_GT(max_error, 0.0) << what << ": stored losslessly";
  cv::Mat observed_mapped, observed_read, differ;
  cv::compare(mapped, 0.0f, observed_mapped, cv::CMP_GT);
  cv::compare(read, 0.0f, observed_read, cv::CMP_GT);
  cv::bitwise_xor(observed_mapped, observed_read, differ);
  EXPECT_EQ(cv::countNonZero(differ), 0) << what;
}

/// Bytes of the keyframes' tile column of a session file.
double TileBytes(const std::string& path) {
  sqlite3* db = nullptr;
  sqlite3_open(path.c_str(), &db);
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "SELECT sum(length(tile)) FROM keyframes", -1, &s, nullptr);
  const double bytes = sqlite3_step(s) == SQLITE_ROW ? sqlite3_column_double(s, 0) : 0.0;
  sqlite3_finalize(s);
  sqlite3_close(db);
  return bytes;
}

bool SameBytes(const cv::Mat& a, const cv::Mat& b) {
  if (a.rows != b.rows || a.cols != b.cols || a.type() != b.type()) return false;
  for (int r = 0; r < a.rows; ++r) {
    if (std::memcmp(a.ptr(r), b.ptr(r), a.cols * a.elemSize()) != 0) return false;
  }
  return true;
}

bool SamePose(const Pose2& a, const Pose2& b) {
  return a.x_m == b.x_m && a.y_m == b.y_m && a.yaw_rad == b.yaw_rad;
}

void ExpectSameFeatures(const FeatureSet& a, const FeatureSet& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.norm_type, b.norm_type);
  for (int i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.keypoints[i].pt, b.keypoints[i].pt);
    EXPECT_EQ(a.keypoints[i].size, b.keypoints[i].size);
    EXPECT_EQ(a.keypoints[i].angle, b.keypoints[i].angle);
    EXPECT_EQ(a.keypoints[i].response, b.keypoints[i].response);
    EXPECT_EQ(a.keypoints[i].octave, b.keypoints[i].octave);
  }
  EXPECT_TRUE(SameBytes(a.descriptors, b.descriptors));
}

class SessionFileTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!::uwbsar::testing::MissingSharedData("maps/seed_lab/my_map.yaml").empty()) return;
    config_ = new Config();
    config_->simulator.route.depart_distance_m = 3.0;  // short: a few keyframes and a loop
    const slam::MapRun run = slam::MapSimulation(*config_, ::uwbsar::testing::SeedLabLidarMap(),
                                                 "depart-return", /*seed=*/1);
    saved_ = new SessionData(slam::CaptureSession(run));
    dir_ = new std::string(
        (fs::temp_directory_path() / ("uwbsar_session_test_" + std::to_string(::getpid())))
            .string());
    fs::create_directories(*dir_);
    WriteSession(Path(), *saved_);
  }
  static void TearDownTestSuite() {
    if (dir_) fs::remove_all(*dir_);
    delete config_;
    delete saved_;
    delete dir_;
    config_ = nullptr;
    saved_ = nullptr;
    dir_ = nullptr;
  }
  void SetUp() override { UWBSAR_NEED_SEED_LAB_MAP(); }
  static std::string Path() { return *dir_ + "/session.uwbsar"; }

  static Config* config_;
  static SessionData* saved_;
  static std::string* dir_;
};
Config* SessionFileTest::config_ = nullptr;
SessionData* SessionFileTest::saved_ = nullptr;
std::string* SessionFileTest::dir_ = nullptr;

// Issue 28: a session grew by 706 KiB a keyframe, 630 of them its float32 tile. Compact tiles
// are at most 150 KiB a keyframe; session.lossless_tiles keeps the float32 bytes.
TEST_F(SessionFileTest, CompactTilesAreSmallAndLosslessOnesKeepTheirBytes) {
  const std::string lossless = *dir_ + "/lossless.uwbsar";
  WriteSession(lossless, *saved_, /*lossless_tiles=*/true);
  const SessionData read = ReadSession(lossless, config_);
  ASSERT_EQ(read.keyframes.size(), saved_->keyframes.size());
  for (std::size_t i = 0; i < read.keyframes.size(); ++i) {
    EXPECT_TRUE(SameBytes(read.keyframes[i].detected.Load(), saved_->keyframes[i].detected.Load()))
        << i;
  }
  const double n = static_cast<double>(saved_->keyframes.size());
  const double compact_kib = TileBytes(Path()) / n / 1024.0;
  const double lossless_kib = TileBytes(lossless) / n / 1024.0;
  std::printf("tiles: compact %.1f KiB, lossless %.1f KiB per keyframe\n", compact_kib,
              lossless_kib);
  EXPECT_LE(compact_kib, 150.0);
  EXPECT_GT(lossless_kib, 3.0 * compact_kib);
}

TEST_F(SessionFileTest, RoundTripKeepsPosesTilesFeaturesAndEdges) {
  const auto t0 = std::chrono::steady_clock::now();
  const SessionData loaded = ReadSession(Path(), config_);
  const double load_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const SessionData& a = *saved_;
  ASSERT_GE(a.keyframes.size(), 3u);
  ASSERT_EQ(loaded.keyframes.size(), a.keyframes.size());
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    const SessionKeyframe& x = a.keyframes[i];
    const SessionKeyframe& y = loaded.keyframes[i];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.stamp_ns, y.stamp_ns);
    EXPECT_TRUE(SamePose(x.T_map_anchor, y.T_map_anchor));
    EXPECT_TRUE(SamePose(x.T_odom_anchor, y.T_odom_anchor));
    EXPECT_TRUE(SamePose(x.T_odom_robot, y.T_odom_robot));
    EXPECT_EQ(x.fixed, y.fixed);
    ExpectCompactTile(x.detected.Load(), y.detected.Load(), "tile " + std::to_string(x.id));
    EXPECT_EQ(x.detected_grid.x0_m, y.detected_grid.x0_m);
    EXPECT_EQ(x.detected_grid.rows, y.detected_grid.rows);
    EXPECT_EQ(x.features.grid.cols, y.features.grid.cols);
    EXPECT_EQ(x.features.centre_anchor.x_m, y.features.centre_anchor.x_m);
    ASSERT_EQ(x.features.by_detector.size(), y.features.by_detector.size());
    for (const auto& [kind, f] : x.features.by_detector)
      ExpectSameFeatures(f, y.features.Features(kind));
  }
  ASSERT_EQ(loaded.edges.size(), a.edges.size());
  int calibrated = 0;  // odometry edges that carry their trajectory (what the round trip keeps)
  for (const SessionEdge& e : a.edges) calibrated += e.edge.trajectory >= 0 && e.edge.path_m > 0;
  EXPECT_GT(calibrated, 0);
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].edge.from_id, loaded.edges[i].edge.from_id);
    EXPECT_EQ(a.edges[i].edge.to_id, loaded.edges[i].edge.to_id);
    EXPECT_EQ(a.edges[i].edge.kind, loaded.edges[i].edge.kind);
    EXPECT_TRUE(SamePose(a.edges[i].edge.T_from_to, loaded.edges[i].edge.T_from_to));
    EXPECT_EQ(a.edges[i].edge.information, loaded.edges[i].edge.information);
    EXPECT_EQ(a.edges[i].rejected, loaded.edges[i].rejected);
    // The odometry calibration's inputs (a NaN turn is stored as NULL and read back as NaN).
    EXPECT_EQ(a.edges[i].edge.trajectory, loaded.edges[i].edge.trajectory);
    EXPECT_EQ(a.edges[i].edge.path_m, loaded.edges[i].edge.path_m);
    EXPECT_EQ(std::isnan(a.edges[i].edge.turn_rad), std::isnan(loaded.edges[i].edge.turn_rad));
    if (!std::isnan(a.edges[i].edge.turn_rad)) {
      EXPECT_EQ(a.edges[i].edge.turn_rad, loaded.edges[i].edge.turn_rad);
    }
  }
  ASSERT_EQ(loaded.loops.size(), a.loops.size());
  for (std::size_t i = 0; i < a.loops.size(); ++i) {
    EXPECT_EQ(loaded.loops[i].good_matches, a.loops[i].good_matches);
    EXPECT_EQ(loaded.loops[i].reason, a.loops[i].reason);
  }
  EXPECT_EQ(loaded.odometry.size(), a.odometry.size());
  EXPECT_EQ(loaded.config_yaml, a.config_yaml);
  const double bytes = static_cast<double>(fs::file_size(Path()));
  std::printf("session: %zu keyframes, %.1f KiB per keyframe, loaded in %.1f ms\n",
              a.keyframes.size(), bytes / 1024.0 / static_cast<double>(a.keyframes.size()),
              load_s * 1e3);
}

TEST_F(SessionFileTest, IncompatibleConfigurationIsRefusedNamingTheKey) {
  Config other = *config_;
  other.imaging.pixel_size_m *= 2;
  const std::string error = ErrorOf([&] { ReadSession(Path(), &other); });
  EXPECT_NE(error.find("imaging.pixel_size_m"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
  Config features = *config_;
  features.place_recognition.detectors.max_keypoints += 1;
  const std::string error2 = ErrorOf([&] { ReadSession(Path(), &features); });
  EXPECT_NE(error2.find("place_recognition.detectors.max_keypoints"), std::string::npos) << error2;
  // Settings that do not change tiles or features are compatible.
  Config fine = *config_;
  fine.backend.loop_rejection_chi2 += 1;
  fine.imaging.num_threads = 3;
  EXPECT_EQ(ErrorOf([&] { ReadSession(Path(), &fine); }), "");
}

TEST_F(SessionFileTest, ForeignDamagedAndOtherVersionFilesAreRefused) {
  const std::string text = *dir_ + "/text.uwbsar";
  std::ofstream(text) << "hello, not a database\n";
  EXPECT_NE(ErrorOf([&] { ReadSession(text); }).find("not a uwbsar session"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadSession(*dir_ + "/missing.uwbsar"); }).find("no session file"),
            std::string::npos);

  const std::string foreign = *dir_ + "/foreign.db3";
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(foreign.c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "CREATE TABLE messages (id INTEGER)", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  EXPECT_NE(ErrorOf([&] { ReadSession(foreign); }).find("not a uwbsar session"), std::string::npos);

  const std::string future = *dir_ + "/future.uwbsar";
  fs::copy_file(Path(), future);
  ASSERT_EQ(sqlite3_open(future.c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "UPDATE meta SET value = '99' WHERE key = 'format_version'", nullptr, nullptr,
               nullptr);
  sqlite3_close(db);
  EXPECT_NE(ErrorOf([&] { ReadSession(future); }).find("format version 99"), std::string::npos);

  // Version 1 had no calibration columns on its edges: it reads, its edges uncalibrated
  // (and, as versions up to 3, its loops' good-match counts in akaze_good and orb_good).
  const std::string version1 = *dir_ + "/version1.uwbsar";
  fs::copy_file(Path(), version1);
  ASSERT_EQ(sqlite3_open(version1.c_str(), &db), SQLITE_OK);
  for (const char* sql :
       {testing::kLoopsToVersion3Sql, "ALTER TABLE edges DROP COLUMN trajectory",
        "ALTER TABLE edges DROP COLUMN path_m", "ALTER TABLE edges DROP COLUMN turn_rad",
        "UPDATE meta SET value = '1' WHERE key = 'format_version'"}) {
    ASSERT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, nullptr), SQLITE_OK) << sql;
  }
  sqlite3_close(db);
  const SessionData old = ReadSession(version1);
  EXPECT_EQ(old.format_version, 1);
  ASSERT_FALSE(old.edges.empty());
  for (const SessionEdge& e : old.edges) EXPECT_EQ(e.edge.trajectory, -1);

  const std::string truncated = *dir_ + "/truncated.uwbsar";
  fs::copy_file(Path(), truncated);
  fs::resize_file(truncated, fs::file_size(Path()) / 2);
  EXPECT_NE(ErrorOf([&] { ReadSession(truncated); }), "");

  const std::string damaged = *dir_ + "/damaged.uwbsar";
  fs::copy_file(Path(), damaged);
  ASSERT_EQ(sqlite3_open(damaged.c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "UPDATE keyframes SET tile = x'0102030405060708090a0b0c0d' WHERE id = 1",
               nullptr, nullptr, nullptr);
  sqlite3_close(db);
  EXPECT_NE(ErrorOf([&] { ReadSession(damaged); }).find("keyframes row 2: tile"),
            std::string::npos);
}

TEST(BlobCodecTest, FloatImagesAndKeypointsAreLossless) {
  cv::Mat m(37, 53, CV_32FC1);
  cv::randn(m, 0.0, 1.0);
  m.at<float>(3, 4) = std::numeric_limits<float>::quiet_NaN();
  m.at<float>(5, 6) = -0.0f;
  const cv::Mat back = session::DecodeMat(session::EncodeMat(m, 3), "m");
  ASSERT_EQ(back.type(), CV_32FC1);
  for (int r = 0; r < m.rows; ++r) {
    EXPECT_EQ(std::memcmp(m.ptr(r), back.ptr(r), m.cols * sizeof(float)), 0);
  }
  std::vector<cv::KeyPoint> k = {cv::KeyPoint(1.5f, 2.25f, 7.f, 33.f, 0.125f, 2, -1)};
  const auto kb = session::DecodeKeypoints(session::EncodeKeypoints(k, 3), "k");
  ASSERT_EQ(kb.size(), 1u);
  EXPECT_EQ(kb[0].pt, k[0].pt);
  EXPECT_EQ(kb[0].octave, 2);
  std::vector<unsigned char> blob = session::EncodeMat(m, 3);
  blob.resize(blob.size() - 5);
  EXPECT_THROW(session::DecodeMat(blob, "m"), InputError);
  blob[0] = 0xff;
  blob[3] = 0x7f;
  EXPECT_THROW(session::DecodeMat(blob, "m"), InputError);
}

TEST(BlobCodecTest, CompactTilesKeepTheObservedPixelsAndRefuseABadStep) {
  cv::Mat tile(20, 30, CV_32FC1, cv::Scalar(0));
  tile.at<float>(1, 2) = 1e-6f;  // far below a level: still observed after the round trip
  tile.at<float>(4, 5) = 7.0f;   // the maximum
  tile.at<float>(6, 7) = 3.3f;
  const std::vector<unsigned char> blob = session::EncodeTile(tile, false, 3);
  const cv::Mat back = session::DecodeTile(blob, "t");
  ASSERT_EQ(back.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(back.at<float>(4, 5), 7.0f);
  EXPECT_NEAR(back.at<float>(6, 7), 3.3f, 0.5 * 7.0 / session::kTileLevels);
  EXPECT_FLOAT_EQ(back.at<float>(1, 2), 7.0f / session::kTileLevels);
  EXPECT_EQ(cv::countNonZero(back), 3);
  // Older sessions' float32 tiles read through the same call.
  const cv::Mat lossless = session::DecodeTile(session::EncodeTile(tile, true, 3), "t");
  EXPECT_EQ(lossless.at<float>(6, 7), 3.3f);
  // A damaged step: named, refused.
  std::vector<unsigned char> bad = blob;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(bad.data() + 12, &nan, sizeof(nan));
  EXPECT_THROW(session::DecodeTile(bad, "t"), InputError);
  bad.resize(14);
  EXPECT_THROW(session::DecodeTile(bad, "t"), InputError);
  // A descriptor type is not a tile.
  EXPECT_THROW(session::DecodeTile(session::EncodeMat(cv::Mat(3, 3, CV_8UC1), 3), "t"), InputError);
}

}  // namespace
}  // namespace uwbsar
