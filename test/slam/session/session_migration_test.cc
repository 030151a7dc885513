// Session format version 4 keeps loops' good-match counts per detector (loop_matches) and
// features of whichever detectors place_recognition.validation.detectors names. Sessions of
// versions 1 to 3 (AKAZE and ORB only, counts in akaze_good / orb_good) must still open:
// a stored version 3 file (written by the version 3 writer) and a freshly rewritten one read
// their counts as AKAZE and ORB entries. A session of another pair round-trips, and is refused,
// naming the key, under a configuration whose pair it holds no features of.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "slam/app_config.h"
#include "slam/session/session_file.h"
#include "test/slam/session/session_test_util.h"
#include "test/slam/session/sqlite_edit.h"
#include "test/slam/session/tiny_session.h"
#include "test/slam/session/version3_loops.h"

namespace uwbsar {
namespace {
namespace fs = std::filesystem;
using testing::ErrorOf;

class SessionMigrationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = (fs::temp_directory_path() /
            ("uwbsar_migration_" + std::to_string(::getpid()) + "_" + info->name()))
               .string();
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static void Sql(const std::string& path, const std::string& sql) {
    ::uwbsar::testing::RunSql(path, sql);
  }

  /// The tiny session's loop (AKAZE 12, ORB 9) and AKAZE and ORB features of each keyframe.
  static void ExpectTinyLoopsAndFeatures(const SessionData& d) {
    ASSERT_EQ(d.loops.size(), 1u);
    const DetectorMap<int> expected = {{DetectorKind::kAkaze, 12}, {DetectorKind::kOrb, 9}};
    EXPECT_EQ(d.loops[0].good_matches, expected);
    EXPECT_EQ(d.loops[0].reason, "accepted");
    ASSERT_EQ(d.keyframes.size(), 3u);
    for (const SessionKeyframe& k : d.keyframes) {
      EXPECT_EQ(k.features.by_detector.size(), 2u);
      EXPECT_EQ(k.features.Features(DetectorKind::kAkaze).size(), 3);
      EXPECT_EQ(k.features.Features(DetectorKind::kOrb).size(), 3);
    }
  }

  std::string dir_;
};

TEST_F(SessionMigrationTest, StoredVersion3FileOpensWithItsCountsAsAkazeAndOrb) {
  // Written by the version 3 writer (the fuzz seed of that time); kept as it was.
  const std::string path =
      std::string(UWBSAR_SOURCE_DIR) + "/test/slam/session/data/tiny_v3.uwbsar";
  const Config config;
  const SessionData d = ReadSession(path, &config);
  EXPECT_EQ(d.format_version, 3);
  ExpectTinyLoopsAndFeatures(d);
  // Saved again it is a version 4 file with the same content.
  const std::string again = dir_ + "/again.uwbsar";
  WriteSession(again, d);
  const SessionData back = ReadSession(again, &config);
  EXPECT_EQ(back.format_version, kSessionFormatVersion);
  ExpectTinyLoopsAndFeatures(back);
}

TEST_F(SessionMigrationTest, Version3LayoutReadsTheOldColumns) {
  const std::string path = dir_ + "/v3.uwbsar";
  WriteSession(path, testing::TinySession());
  Sql(path, std::string(testing::kLoopsToVersion3Sql) +
                "UPDATE meta SET value = '3' WHERE key = 'format_version';");
  const SessionData d = ReadSession(path);
  EXPECT_EQ(d.format_version, 3);
  ExpectTinyLoopsAndFeatures(d);
  // A version 4 file is read by its own layout: without loop_matches it is refused.
  Sql(path, "UPDATE meta SET value = '4' WHERE key = 'format_version'");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path); }), path + ": table loops has no column idx");
}

TEST_F(SessionMigrationTest, AnotherDetectorPairRoundTripsAndIsRefusedUnderThePapersPair) {
  SessionData s = testing::TinySession();
  for (SessionKeyframe& k : s.keyframes) {
    k.features.by_detector.erase(DetectorKind::kAkaze);
    k.features.by_detector[DetectorKind::kBrisk] =
        testing::TinyFeatures(DetectorKind::kBrisk, 64, k.id);
  }
  s.loops[0].good_matches = {{DetectorKind::kBrisk, 14}, {DetectorKind::kOrb, 9}};
  const std::string path = dir_ + "/brisk_orb.uwbsar";
  WriteSession(path, s);

  Config brisk_orb;
  brisk_orb.place_recognition.validation.detectors = {DetectorKind::kBrisk, DetectorKind::kOrb};
  const SessionData d = ReadSession(path, &brisk_orb);
  ASSERT_EQ(d.loops.size(), 1u);
  EXPECT_EQ(d.loops[0].good_matches, s.loops[0].good_matches);
  for (const SessionKeyframe& k : d.keyframes) {
    EXPECT_EQ(k.features.Features(DetectorKind::kBrisk).size(), 3);
    EXPECT_EQ(k.features.by_detector.count(DetectorKind::kAkaze), 0u);
  }

  const Config paper;
  EXPECT_EQ(ErrorOf([&] { ReadSession(path, &paper); }),
            path +
                ": incompatible configuration: place_recognition.validation.detectors names "
                "AKAZE, the session holds features of BRISK, ORB");
}

TEST_F(SessionMigrationTest, Version7FilesWithoutChecksumsStillRead) {
  const std::string v8 = dir_ + "/v8.uwbsar", v7 = dir_ + "/v7.uwbsar";
  WriteSession(v8, testing::TinySession());
  fs::copy_file(v8, v7);
  Sql(v7,
      "ALTER TABLE keyframes DROP COLUMN tile_xxh3; "
      "ALTER TABLE features DROP COLUMN keypoints_xxh3; "
      "ALTER TABLE features DROP COLUMN descriptors_xxh3; "
      "ALTER TABLE edges DROP COLUMN information_xxh3; "
      "UPDATE meta SET value = '7' WHERE key = 'format_version'");
  const SessionData d = ReadSession(v7), checked = ReadSession(v8);
  EXPECT_EQ(d.format_version, 7);
  ExpectTinyLoopsAndFeatures(d);
  for (std::size_t i = 0; i < d.keyframes.size(); ++i) {
    EXPECT_EQ(cv::norm(d.keyframes[i].detected.Load(), checked.keyframes[i].detected.Load(),
                       cv::NORM_INF),
              0.0);
  }
  // A version 8 file without its checksums is refused naming the column.
  Sql(v7, "UPDATE meta SET value = '8' WHERE key = 'format_version'");
  EXPECT_EQ(ErrorOf([&] { ReadSession(v7); }), v7 + ": table keyframes has no column tile_xxh3");
  Sql(v7, "UPDATE meta SET value = '7' WHERE key = 'format_version'");
  // Version 7 stored a run carried over from a version 1 or 2 session as "": still read so.
  Sql(v7, "UPDATE trajectories SET fingerprint = ''");
  const SessionData carried = ReadSession(v7);
  EXPECT_EQ(carried.trajectories.at(0).fingerprint, "");
  // Saved again (version 8: checksums), such a run is stored as unknown, never empty.
  const std::string again = dir_ + "/again.uwbsar";
  WriteSession(again, carried);
  EXPECT_EQ(testing::SqlText(again, "SELECT fingerprint FROM trajectories"),
            kUnknownRunFingerprint);
  EXPECT_EQ(ReadSession(again).trajectories.at(0).fingerprint, "");
}

TEST(SessionFormatDocTest, FormatsMdNamesTheVersionThisUwbsarWrites) {
  std::ifstream in(std::string(UWBSAR_SOURCE_DIR) + "/docs/formats.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string v = std::to_string(kSessionFormatVersion);
  EXPECT_NE(text.str().find("(format version " + v + ", which also reads versions 1 to " +
                            std::to_string(kSessionFormatVersion - 1)),
            std::string::npos)
      << "docs/formats.md, Session file: the version is " << v;
}

}  // namespace
}  // namespace uwbsar
