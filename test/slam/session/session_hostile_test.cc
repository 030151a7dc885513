// The session reader on hostile files (issue 26, items 8, 9 and 12): columns are read by name
// (their order does not matter, a missing one is refused naming it), every value is
// range-checked (resolutions, NULLs, non-finite tiles, ids beyond INT_MAX) with one line
// "<file>: <table> row <n>: <column> <what is wrong>", sizes a session implies are checked
// before allocation (a declared 16000 x 16000 tile, a map extent beyond
// limits.max_image_pixels), joins after ids near INT_MAX do not wrap, and a full disk while
// writing is an I/O failure naming the path and "no space left on device".
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zstd.h>

#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include "core/errors.h"
#include "slam/outputs/session_mosaic.h"
#include "slam/session/blob_checksum.h"
#include "slam/session/blob_codec.h"
#include "slam/session/session_file.h"
#include "slam/session/session_merge.h"
#include "test/slam/session/session_test_util.h"
#include "test/slam/session/sqlite_edit.h"
#include "test/slam/session/tiny_session.h"
#include "test/slam/session/version3_loops.h"

namespace uwbsar {
namespace {
namespace fs = std::filesystem;
using testing::ErrorOf;

class SessionHostileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = (fs::temp_directory_path() /
            ("uwbsar_hostile_" + std::to_string(::getpid()) + "_" + info->name()))
               .string();
    fs::create_directories(dir_);
    saved_ = ::uwbsar::testing::TinySession();
    path_ = dir_ + "/session.uwbsar";
    WriteSession(path_, saved_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void Sql(const std::string& sql) { ::uwbsar::testing::RunSql(path_, sql); }
  /// Sets blob `column` of `table`'s rows `where` to `blob`, and its checksum column (format
  /// version 8) to match: a hostile file, not a damaged one, so the checks behind the checksum
  /// are what refuses it.
  void SetBlob(const std::string& table, const std::string& column, const std::string& where,
               const std::vector<unsigned char>& blob) {
    const std::string checksum = session::ChecksumColumn(column);
    const bool has_checksum =
        ::uwbsar::testing::SqlText(path_, "SELECT count(*) FROM pragma_table_info('" + table +
                                              "') WHERE name = '" + checksum + "'") == "1";
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    const std::string sql = "UPDATE " + table + " SET " + column + " = ?1" +
                            (has_checksum ? ", " + checksum + " = ?2" : "") + " WHERE " + where;
    ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr), SQLITE_OK);
    sqlite3_bind_blob64(s, 1, blob.data(), blob.size(), SQLITE_TRANSIENT);
    if (has_checksum) sqlite3_bind_int64(s, 2, session::BlobChecksum(blob));
    EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
    sqlite3_finalize(s);
    sqlite3_close(db);
  }
  void SetBlob(const std::string& column, int id, const std::vector<unsigned char>& blob) {
    SetBlob("keyframes", column, "id = " + std::to_string(id), blob);
  }

  std::string dir_, path_;
  SessionData saved_;
};

TEST_F(SessionHostileTest, SwappedColumnsAreReadByName) {
  // x_m and y_m change places (each keeps its name and its values): the placement is the same.
  Sql("ALTER TABLE keyframes RENAME COLUMN x_m TO tmp_x; "
      "ALTER TABLE keyframes RENAME COLUMN y_m TO x_m; "
      "ALTER TABLE keyframes RENAME COLUMN tmp_x TO y_m; "
      "UPDATE keyframes SET x_m = y_m, y_m = x_m; "
      "ALTER TABLE odometry RENAME COLUMN x_m TO tmp_x; "
      "ALTER TABLE odometry RENAME COLUMN y_m TO x_m; "
      "ALTER TABLE odometry RENAME COLUMN tmp_x TO y_m; "
      "UPDATE odometry SET x_m = y_m, y_m = x_m;");
  const SessionData read = ReadSession(path_);
  ASSERT_EQ(read.keyframes.size(), saved_.keyframes.size());
  for (std::size_t i = 0; i < read.keyframes.size(); ++i) {
    EXPECT_EQ(read.keyframes[i].T_map_anchor.x_m, saved_.keyframes[i].T_map_anchor.x_m) << i;
    EXPECT_EQ(read.keyframes[i].T_map_anchor.y_m, saved_.keyframes[i].T_map_anchor.y_m) << i;
  }
  ASSERT_EQ(read.odometry.size(), saved_.odometry.size());
  EXPECT_EQ(read.odometry[3].T_odom_robot.x_m, saved_.odometry[3].T_odom_robot.x_m);
  EXPECT_EQ(read.odometry[3].T_odom_robot.y_m, saved_.odometry[3].T_odom_robot.y_m);
}

TEST_F(SessionHostileTest, MissingColumnIsRefusedNamingIt) {
  Sql("ALTER TABLE keyframes DROP COLUMN centre_y_m");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": table keyframes has no column centre_y_m");
}

TEST_F(SessionHostileTest, TinyFeatureResolutionIsRefused) {
  Sql("UPDATE keyframes SET feature_resolution_m = 1e-300 WHERE id = 1");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": keyframes row 2: feature_resolution_m 1e-300 is outside [0.0001, 10]");
}

TEST_F(SessionHostileTest, NullOdometryIsRefused) {
  Sql("UPDATE odometry SET y_m = NULL WHERE rowid = 3");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }), path_ + ": odometry row 3: y_m is NULL");
}

TEST_F(SessionHostileTest, InfiniteTileIsRefused) {
  cv::Mat tile = saved_.keyframes[1].detected.Load().clone();
  tile.at<float>(2, 3) = std::numeric_limits<float>::infinity();
  SetBlob("tile", 1, session::EncodeMat(tile, 3));
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": keyframes row 2: tile has non-finite pixels");
}

TEST_F(SessionHostileTest, TextWhereANumberBelongsIsRefused) {
  Sql("UPDATE keyframes SET stamp_ns = 'yesterday' WHERE id = 0");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": keyframes row 1: stamp_ns is not an integer ('yesterday')");
}

TEST_F(SessionHostileTest, InformationThatIsNotPositiveDefiniteIsRefused) {
  // The loop edge's information with a negative yaw weight (diag 100, 100, -400).
  const double v[9] = {100, 0, 0, 0, 100, 0, 0, 0, -400};
  std::vector<unsigned char> blob(sizeof(v));
  std::memcpy(blob.data(), v, sizeof(v));
  SetBlob("edges", "information", "idx = 2", blob);
  EXPECT_EQ(
      ErrorOf([&] { ReadSession(path_); }),
      path_ + ": edges row 3: information is not a finite symmetric positive definite matrix");
}

TEST_F(SessionHostileTest, LoopToAMissingKeyframeIsRefused) {
  Sql("UPDATE loops SET match_id = 7");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": loops row 1: match_id 7 is not a keyframe");
}

TEST_F(SessionHostileTest, AnchorsAreReadAndOneFollowingNoKeyframeIsRefused) {
  // A retired keyframe (slam.place_views) following keyframe 1, and one in the map frame.
  Sql("INSERT INTO anchors VALUES (50, 0, 1700000000000000000, 1, 2, 0.1, 1, 0.5, 0, 0); "
      "INSERT INTO anchors VALUES (51, 0, 1700000001000000000, 2, 2, 0.1, -1, 3, 4, 0.2)");
  const SessionData d = ReadSession(path_);
  ASSERT_EQ(d.anchors.size(), 2u);
  EXPECT_EQ(d.anchors[0].hub_id, 1);
  const std::map<int, Pose2> poses = d.Poses();
  EXPECT_NEAR(d.anchors[0].MapPose(poses)->x_m, (poses.at(1) * Pose2{0.5, 0, 0}).x_m, 1e-12);
  EXPECT_NEAR(d.anchors[1].MapPose(poses)->y_m, 4.0, 1e-12);
  EXPECT_EQ(d.MaxKeyframeId(), 51);  // a join numbers its keyframes past the anchors
  Sql("UPDATE anchors SET hub_id = 7 WHERE id = 50");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": anchors row 1: hub_id 7 is not a keyframe");
  Sql("UPDATE anchors SET hub_id = 1, id = 1 WHERE id = 50");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }), path_ + ": anchors row 1: id 1 is already used");
}

TEST_F(SessionHostileTest, DenormalTileStepRepeatedOdometryStampAndSelfLoopAreRefused) {
  // A compact tile whose step is the smallest denormal: every level would read as 0 or a
  // denormal, a blank tile.
  std::vector<unsigned char> tile =
      session::EncodeTile(saved_.keyframes[1].detected.Load(), false, 3);
  const float denormal = 1e-45f;
  std::memcpy(tile.data() + 12, &denormal, sizeof(denormal));
  SetBlob("tile", 1, tile);
  EXPECT_EQ(ErrorOf([&] {
              ReadSession(path_);
            }).rfind(path_ + ": keyframes row 2: tile: damaged blob (step 1.4013e-45 ", 0),
            0u)
      << ErrorOf([&] { ReadSession(path_); });
  // Odometry stamps repeated or going back within a run.
  WriteSession(path_, saved_);
  const std::string second = std::to_string(saved_.odometry[1].stamp_ns);
  Sql("UPDATE odometry SET stamp_ns = " + second + " WHERE rowid = 3");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }), path_ + ": odometry row 3: stamp_ns " + second +
                                                      " is not after row 2's (" + second +
                                                      ") of trajectory 0");
  Sql("UPDATE odometry SET stamp_ns = " + std::to_string(saved_.odometry[0].stamp_ns) +
      " WHERE rowid = 3");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": odometry row 3: stamp_ns " + std::to_string(saved_.odometry[0].stamp_ns) +
                " is not after row 2's (" + second + ") of trajectory 0");
  // A loop from a keyframe to itself.
  WriteSession(path_, saved_);
  Sql("UPDATE loops SET match_id = query_id");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }), path_ + ": loops row 1: match_id " +
                                                      std::to_string(saved_.loops[0].query_id) +
                                                      " equals query_id");
}

TEST_F(SessionHostileTest, IdBeyondIntMaxIsRefusedNotWrapped) {
  Sql("PRAGMA foreign_keys = OFF; UPDATE keyframes SET id = 4294967298 WHERE id = 2");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": keyframes row 3: id 4294967298 is outside [0, 2147483647]");
}

TEST_F(SessionHostileTest, IdsNearIntMaxAreReadAndAJoinDoesNotWrap) {
  const std::string big = std::to_string(INT_MAX);
  Sql("UPDATE keyframes SET id = " + big + " WHERE id = 2; UPDATE features SET keyframe_id = " +
      big + " WHERE keyframe_id = 2; UPDATE edges SET to_id = " + big +
      " WHERE to_id = 2; UPDATE loops SET query_id = " + big +
      " WHERE query_id = 2; UPDATE trajectories SET id = " + big +
      "; UPDATE keyframes SET trajectory = " + big + "; UPDATE odometry SET trajectory = " + big +
      "; UPDATE edges SET trajectory = " + big + " WHERE trajectory = 0");
  const SessionData a = ReadSession(path_);
  ASSERT_EQ(a.keyframes.size(), 3u);
  EXPECT_EQ(a.keyframes[2].id, INT_MAX);
  EXPECT_EQ(a.trajectories[0].id, INT_MAX);

  MergeReport report;
  const SessionData joined =
      MergeSessions(a, ::uwbsar::testing::TinySession(), SessionSettings(Config()), &report);
  EXPECT_TRUE(report.renumbered);
  EXPECT_EQ(report.id_offset, 3);          // a renumbered 0, 1, 2
  EXPECT_EQ(report.trajectory_offset, 1);  // a's run is 0, the new one 1
  for (const SessionKeyframe& k : joined.keyframes) {
    EXPECT_GE(k.id, 0);
    EXPECT_LE(k.id, 5);
  }
  ASSERT_EQ(joined.trajectories.size(), 2u);
  EXPECT_EQ(joined.trajectories[1].id, 1);
  // The joined session saves and reads again (the next resume starts from it).
  const std::string again = dir_ + "/joined.uwbsar";
  WriteSession(again, joined);
  const SessionData back = ReadSession(again);
  EXPECT_EQ(back.keyframes.size(), joined.keyframes.size());
  EXPECT_EQ(back.MaxKeyframeId(), joined.MaxKeyframeId());
}

/// A tile blob declaring rows x cols float pixels of zeros (a few MB for 16000 x 16000).
std::vector<unsigned char> DeclaredTile(int rows, int cols) {
  const std::int32_t header[3] = {rows, cols, CV_32FC1};
  std::vector<unsigned char> out(sizeof(header));
  std::memcpy(out.data(), header, sizeof(header));
  const std::size_t n = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols) * 4;
  ZSTD_CCtx* c = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(c, ZSTD_c_compressionLevel, 1);
  ZSTD_CCtx_setPledgedSrcSize(c, n);
  const std::vector<char> zeros(1 << 22, 0);
  std::vector<unsigned char> chunk(ZSTD_CStreamOutSize());
  for (std::size_t done = 0; done < n;) {
    const std::size_t take = std::min(zeros.size(), n - done);
    done += take;
    ZSTD_inBuffer in{zeros.data(), take, 0};
    const ZSTD_EndDirective mode = done == n ? ZSTD_e_end : ZSTD_e_continue;
    for (bool finished = false; !finished;) {
      ZSTD_outBuffer o{chunk.data(), chunk.size(), 0};
      const std::size_t left = ZSTD_compressStream2(c, &o, &in, mode);
      out.insert(out.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(o.pos));
      finished = mode == ZSTD_e_end ? left == 0 : in.pos == in.size;
    }
  }
  ZSTD_freeCCtx(c);
  return out;
}

long PeakRssKiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

TEST_F(SessionHostileTest, HugeDeclaredTileIsRefusedBeforeAllocation) {
  SetBlob("tile", 0, DeclaredTile(16000, 16000));
  std::printf("session with a declared 16000 x 16000 tile: %.1f MB\n",
              static_cast<double>(fs::file_size(path_)) / 1e6);
  const long before_kib = PeakRssKiB();
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ +
                ": keyframes row 1: tile: declares 16000 x 16000 pixels, more than "
                "limits.max_tile_pixels (3.2e+07); refused before decoding");
  const long grown_kib = PeakRssKiB() - before_kib;
  std::printf("peak memory grew by %.1f MB while refusing it\n",
              static_cast<double>(grown_kib) / 1024.0);
  EXPECT_LT(grown_kib, 100 * 1024);  // the tile alone would be 1024 MB, twice over
}

TEST_F(SessionHostileTest, MapExtentBeyondMaxImagePixelsIsRefusedNamingTheFile) {
  const Config config;
  ImageGrid grid;
  cv::Mat observed;
  const cv::Mat fine = slam::RenderSessionMosaic(ReadSession(path_), config, &grid, &observed);
  EXPECT_FALSE(fine.empty());
  // One keyframe moved 2 km along each axis: the mosaic's bounding box would be ~1e10 pixels.
  Sql("UPDATE keyframes SET x_m = x_m + 2000, y_m = y_m + 2000 WHERE id = 1");
  const SessionData moved = ReadSession(path_);
  const std::string error =
      ErrorOf([&] { slam::RenderSessionMosaic(moved, config, &grid, &observed); });
  std::printf("%s\n", error.c_str());
  EXPECT_EQ(error.rfind(path_ + ": the map of its keyframes spans x ", 0), 0u) << error;
  EXPECT_NE(error.find("more than limits.max_image_pixels (2e+08); refused before allocation"),
            std::string::npos)
      << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
}

TEST_F(SessionHostileTest, Version2FilesReadWithoutFingerprintsAndVersion3KeepsThem) {
  EXPECT_EQ(ReadSession(path_).trajectories.at(0).fingerprint, saved_.trajectories[0].fingerprint);
  Sql(std::string(testing::kLoopsToVersion3Sql) +
      "ALTER TABLE trajectories DROP COLUMN fingerprint; "
      "UPDATE meta SET value = '2' WHERE key = 'format_version'");
  const SessionData old = ReadSession(path_);
  EXPECT_EQ(old.format_version, 2);
  EXPECT_EQ(old.trajectories.at(0).fingerprint, "");
  Sql("UPDATE meta SET value = '3' WHERE key = 'format_version'");
  EXPECT_EQ(ErrorOf([&] { ReadSession(path_); }),
            path_ + ": table trajectories has no column fingerprint");
}

// ---- a full disk, simulated by an sqlite VFS whose writes past a quota fail as ENOSPC would.

sqlite3_vfs* g_real_vfs = nullptr;
sqlite3_int64 g_quota_bytes = 0;

struct QuotaFile {
  sqlite3_file base;
  sqlite3_file* real;  // the real VFS's file, allocated right after this struct
};

sqlite3_file* Real(sqlite3_file* f) { return reinterpret_cast<QuotaFile*>(f)->real; }

int QuotaWrite(sqlite3_file* f, const void* data, int n, sqlite3_int64 offset) {
  if (offset + n > g_quota_bytes) return SQLITE_FULL;
  return Real(f)->pMethods->xWrite(Real(f), data, n, offset);
}
int QuotaClose(sqlite3_file* f) { return Real(f)->pMethods->xClose(Real(f)); }
int QuotaRead(sqlite3_file* f, void* data, int n, sqlite3_int64 offset) {
  return Real(f)->pMethods->xRead(Real(f), data, n, offset);
}
int QuotaTruncate(sqlite3_file* f, sqlite3_int64 size) {
  return Real(f)->pMethods->xTruncate(Real(f), size);
}
int QuotaSync(sqlite3_file* f, int flags) { return Real(f)->pMethods->xSync(Real(f), flags); }
int QuotaFileSize(sqlite3_file* f, sqlite3_int64* size) {
  return Real(f)->pMethods->xFileSize(Real(f), size);
}
int QuotaLock(sqlite3_file* f, int lock) { return Real(f)->pMethods->xLock(Real(f), lock); }
int QuotaUnlock(sqlite3_file* f, int lock) { return Real(f)->pMethods->xUnlock(Real(f), lock); }
int QuotaCheckReservedLock(sqlite3_file* f, int* out) {
  return Real(f)->pMethods->xCheckReservedLock(Real(f), out);
}
int QuotaFileControl(sqlite3_file* f, int op, void* arg) {
  return Real(f)->pMethods->xFileControl(Real(f), op, arg);
}
int QuotaSectorSize(sqlite3_file* f) { return Real(f)->pMethods->xSectorSize(Real(f)); }
int QuotaDeviceCharacteristics(sqlite3_file* f) {
  return Real(f)->pMethods->xDeviceCharacteristics(Real(f));
}

const sqlite3_io_methods kQuotaMethods = {1,
                                          QuotaClose,
                                          QuotaRead,
                                          QuotaWrite,
                                          QuotaTruncate,
                                          QuotaSync,
                                          QuotaFileSize,
                                          QuotaLock,
                                          QuotaUnlock,
                                          QuotaCheckReservedLock,
                                          QuotaFileControl,
                                          QuotaSectorSize,
                                          QuotaDeviceCharacteristics,
                                          nullptr,
                                          nullptr,
                                          nullptr,
                                          nullptr,
                                          nullptr,
                                          nullptr};

int QuotaOpen(sqlite3_vfs*, const char* name, sqlite3_file* f, int flags, int* out_flags) {
  QuotaFile* q = reinterpret_cast<QuotaFile*>(f);
  q->real = reinterpret_cast<sqlite3_file*>(q + 1);
  const int rc = g_real_vfs->xOpen(g_real_vfs, name, q->real, flags, out_flags);
  q->base.pMethods = rc == SQLITE_OK ? &kQuotaMethods : nullptr;
  return rc;
}

TEST_F(SessionHostileTest, DiskFullWhileWritingIsAnIoFailureNamingTheCause) {
  g_real_vfs = sqlite3_vfs_find(nullptr);
  ASSERT_NE(g_real_vfs, nullptr);
  sqlite3_vfs quota = *g_real_vfs;
  quota.zName = "uwbsar-quota";
  quota.szOsFile = static_cast<int>(sizeof(QuotaFile)) + g_real_vfs->szOsFile;
  quota.xOpen = QuotaOpen;
  g_quota_bytes = 8192;  // two pages: the schema fits, the keyframes do not
  ASSERT_EQ(sqlite3_vfs_register(&quota, /*makeDflt=*/1), SQLITE_OK);
  const std::string full = dir_ + "/full.uwbsar";
  std::string message;
  bool input_error = false;
  try {
    WriteSession(full, saved_);
  } catch (const InputError& e) {
    input_error = true;
    message = e.what();
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  sqlite3_vfs_unregister(&quota);
  sqlite3_vfs_register(g_real_vfs, 1);
  EXPECT_FALSE(input_error) << message;
  EXPECT_EQ(message, full + ": cannot write: no space left on device");
  EXPECT_FALSE(fs::exists(full));
  int left = 0;  // nor a temporary file
  for (const auto& e : fs::directory_iterator(dir_))
    left += e.path().filename() != "session.uwbsar";
  EXPECT_EQ(left, 0);
}

// How fuzz/corpus/session/ was made: UWBSAR_FUZZ_SEED_DIR=fuzz/corpus/session
// build/bin/session_tests --gtest_filter='TinySessionSeed.*' (tiny.uwbsar, and swapped.uwbsar
// with keyframes.x_m and y_m in the other order; 512-byte pages, a few KB each).
TEST(TinySessionSeed, WritesTheFuzzSeedsWhenAsked) {
  const char* dir = std::getenv("UWBSAR_FUZZ_SEED_DIR");
  if (dir == nullptr) GTEST_SKIP() << "UWBSAR_FUZZ_SEED_DIR not set";
  for (const std::string name : {"tiny", "swapped"}) {
    const std::string path = std::string(dir) + "/" + name + ".uwbsar";
    WriteSession(path, ::uwbsar::testing::TinySession());
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    if (name == "swapped") {
      ASSERT_EQ(sqlite3_exec(db,
                             "ALTER TABLE keyframes RENAME COLUMN x_m TO tmp_x; "
                             "ALTER TABLE keyframes RENAME COLUMN y_m TO x_m; "
                             "ALTER TABLE keyframes RENAME COLUMN tmp_x TO y_m; "
                             "UPDATE keyframes SET x_m = y_m, y_m = x_m;",
                             nullptr, nullptr, nullptr),
                SQLITE_OK);
    }
    ASSERT_EQ(sqlite3_exec(db, "PRAGMA page_size = 512; VACUUM;", nullptr, nullptr, nullptr),
              SQLITE_OK);
    sqlite3_close(db);
    EXPECT_EQ(ReadSession(path).keyframes.size(), 3u);
  }
}

}  // namespace
}  // namespace uwbsar
