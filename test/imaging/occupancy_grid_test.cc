#include "imaging/occupancy_grid.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "test/shared_data.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

/// A fresh folder per test holding hand-written map files.
class OccupancyGridTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("uwbsar_grid_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& bytes) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  /// 3 x 2 P5 image: top row 0 254 205, bottom row 254 254 0.
  std::string WriteSmallPgm() {
    return Write("m.pgm", std::string("P5\n# comment\n3 2\n255\n") +
                              std::string("\x00\xfe\xcd\xfe\xfe\x00", 6));
  }
  std::string Yaml(const std::string& extra) {
    return Write("m.yaml", "image: m.pgm\nresolution: 0.5\norigin: [1.0, -2.0, 0.0]\n" + extra);
  }

  fs::path dir_;
};

TEST_F(OccupancyGridTest, TrinaryCellsKeepImageRowOrderAndOrigin) {
  WriteSmallPgm();
  // ROS 1 map_saver's free_thresh: grey 205 (occ 0.196) is then unknown.
  const OccupancyGrid g = LoadOccupancyGrid(Yaml("negate: 0\nfree_thresh: 0.196\n"));
  ASSERT_EQ(g.rows, 2);
  ASSERT_EQ(g.cols, 3);
  EXPECT_EQ(g.At(0, 0), OccupancyGrid::kOccupied);
  EXPECT_EQ(g.At(0, 1), OccupancyGrid::kFree);
  EXPECT_EQ(g.At(0, 2), OccupancyGrid::kUnknown);
  EXPECT_EQ(g.At(1, 2), OccupancyGrid::kOccupied);
  // Row 0 is the top: its centres sit one cell above the bottom row's.
  const Point2 top_left = g.CellCenter(0, 0);
  EXPECT_DOUBLE_EQ(top_left.x_m, 1.25);
  EXPECT_DOUBLE_EQ(top_left.y_m, -2.0 + 0.75);
  const Point2 bottom_right = g.CellCenter(1, 2);
  EXPECT_DOUBLE_EQ(bottom_right.x_m, 1.0 + 1.25);
  EXPECT_DOUBLE_EQ(bottom_right.y_m, -2.0 + 0.25);
  int row = -1, col = -1;
  ASSERT_TRUE(g.CellOf({2.2, -1.9}, &row, &col));
  EXPECT_EQ(row, 1);
  EXPECT_EQ(col, 2);
  EXPECT_FALSE(g.CellOf({0.9, -1.9}, &row, &col));
}

TEST_F(OccupancyGridTest, Grey205IsFreeUnderNav2DefaultFreeThresh) {
  // map_server semantics, faithfully: occ = (255 - 205) / 255 = 0.196 < 0.25 is free.
  WriteSmallPgm();
  EXPECT_EQ(LoadOccupancyGrid(Yaml("")).At(0, 2), OccupancyGrid::kFree);
}

TEST_F(OccupancyGridTest, NegateSwapsFreeAndOccupied) {
  WriteSmallPgm();
  const OccupancyGrid g = LoadOccupancyGrid(Yaml("negate: 1\n"));
  EXPECT_EQ(g.At(0, 0), OccupancyGrid::kFree);
  EXPECT_EQ(g.At(0, 1), OccupancyGrid::kOccupied);
}

TEST_F(OccupancyGridTest, ScaleModeMapsGreyBetweenThresholdsLinearly) {
  // occ = (255 - v) / 255: v = 128 -> 0.498, between free 0.25 and occupied 0.65.
  Write("m.pgm", std::string("P5 2 1 255\n") + std::string("\x80\x00", 2));
  const OccupancyGrid g = LoadOccupancyGrid(Yaml("mode: scale\n"));
  EXPECT_EQ(g.At(0, 0), static_cast<std::int8_t>(std::lround(99.0 * (127.0 / 255 - 0.25) / 0.4)));
  EXPECT_EQ(g.At(0, 1), OccupancyGrid::kOccupied);
  const OccupancyGrid t = LoadOccupancyGrid(Yaml("mode: trinary\n"));
  EXPECT_EQ(t.At(0, 0), OccupancyGrid::kUnknown);
}

TEST_F(OccupancyGridTest, ThresholdsComeFromTheYaml) {
  Write("m.pgm", std::string("P5 1 1 255\n") + std::string("\x80", 1));
  EXPECT_EQ(LoadOccupancyGrid(Yaml("occupied_thresh: 0.4\n")).At(0, 0), OccupancyGrid::kOccupied);
  EXPECT_EQ(LoadOccupancyGrid(Yaml("free_thresh: 0.6\n")).At(0, 0), OccupancyGrid::kFree);
}

TEST_F(OccupancyGridTest, RawModeKeepsValuesUpTo100) {
  Write("m.pgm", std::string("P5 3 1 255\n") + std::string("\x00\x32\xc8", 3));
  const OccupancyGrid g = LoadOccupancyGrid(Yaml("mode: raw\n"));
  EXPECT_EQ(g.At(0, 0), 0);
  EXPECT_EQ(g.At(0, 1), 50);
  EXPECT_EQ(g.At(0, 2), OccupancyGrid::kUnknown);
}

TEST_F(OccupancyGridTest, AsciiPgmWithSmallMaxvalReads) {
  Write("m.pgm", "P2\n2 2\n15\n0 15\n15 0\n");
  const OccupancyGrid g = LoadOccupancyGrid(Yaml(""));
  EXPECT_EQ(g.At(0, 0), OccupancyGrid::kOccupied);
  EXPECT_EQ(g.At(0, 1), OccupancyGrid::kFree);
  EXPECT_EQ(g.At(1, 1), OccupancyGrid::kOccupied);
}

TEST_F(OccupancyGridTest, OriginYawRotatesCellCentres) {
  WriteSmallPgm();
  const OccupancyGrid g = LoadOccupancyGrid(
      Write("m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0, 1.5707963267948966]\n"));
  const Point2 p = g.CellCenter(1, 0);  // (0.5, 0.5) in the map frame
  EXPECT_NEAR(p.x_m, -0.5, 1e-12);
  EXPECT_NEAR(p.y_m, 0.5, 1e-12);
}

std::string ErrorOf(const std::string& yaml_path) {
  try {
    LoadOccupancyGrid(yaml_path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(OccupancyGridTest, MissingImageIsAnErrorNamingIt) {
  const std::string msg = ErrorOf(Yaml(""));
  EXPECT_NE(msg.find("m.pgm"), std::string::npos) << msg;
  EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
}

TEST_F(OccupancyGridTest, TruncatedPgmIsAnError) {
  Write("m.pgm", std::string("P5 3 2 255\n") + std::string("\x00\x00\x00", 3));
  const std::string msg = ErrorOf(Yaml(""));
  EXPECT_NE(msg.find("bad PGM size"), std::string::npos) << msg;
  Write("m.pgm", "P2 2 2 255\n0 0 0\n");
  EXPECT_NE(ErrorOf(Yaml("")).find("bad PGM size"), std::string::npos);
}

TEST_F(OccupancyGridTest, BadPgmHeaderIsAnError) {
  Write("m.pgm", "P7 2 2 255\n");
  EXPECT_NE(ErrorOf(Yaml("")).find("bad PGM header"), std::string::npos);
  Write("m.pgm", "P5 2 x 255\n");
  EXPECT_NE(ErrorOf(Yaml("")).find("invalid height"), std::string::npos);
  Write("m.pgm", "P5 2 2\n");
  EXPECT_NE(ErrorOf(Yaml("")).find("missing maxval"), std::string::npos);
}

TEST_F(OccupancyGridTest, BadYamlValuesNameKeyAndLine) {
  WriteSmallPgm();
  const std::string res =
      ErrorOf(Write("m.yaml", "image: m.pgm\nresolution: 0\norigin: [0, 0, 0]\n"));
  EXPECT_NE(res.find("m.yaml:2"), std::string::npos) << res;
  EXPECT_NE(res.find("resolution"), std::string::npos) << res;
  EXPECT_NE(ErrorOf(Write("m.yaml", "image: m.pgm\norigin: [0, 0, 0]\n")).find("'resolution'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Yaml("mode: fancy\n")).find("'mode'"), std::string::npos);
  EXPECT_NE(ErrorOf(Yaml("negate: 2\n")).find("'negate'"), std::string::npos);
  EXPECT_NE(ErrorOf(Yaml("free_thresh: 0.9\n")).find("free_thresh"), std::string::npos);
  EXPECT_NE(
      ErrorOf(Write("m.yaml", "image: m.pgm\nresolution: 1\norigin: [0, 0]\n")).find("'origin'"),
      std::string::npos);
  EXPECT_NE(ErrorOf(Write("m.yaml", "image: [\n")).find("syntax"), std::string::npos);
  EXPECT_NE(ErrorOf((dir_ / "none.yaml").string()).find("cannot open"), std::string::npos);
}

// Netpbm allows any maxval 1..65535: samples are scaled by it, so the same map gives the
// same cells whatever maxval and depth it was written with.
TEST_F(OccupancyGridTest, PgmSamplesAreScaledByTheirMaxval) {
  const std::string yaml = "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n";
  // Black, white and map_saver's unknown grey (205 of 255) at several maxvals.
  struct Case {
    std::string pgm;
  } cases[] = {
      {std::string("P5\n3 1\n255\n") + std::string("\x00\xff\xcd", 3)},
      {"P2\n3 1\n1\n0 1 1\n"},  // maxval 1: 1 is white
      {"P2\n3 1\n1000\n0 1000 804\n"},
      {std::string("P5\n3 1\n65535\n") + std::string("\x00\x00\xff\xff\xcd\xcd", 6)},
  };
  for (const Case& c : cases) {
    Write("m.pgm", c.pgm);
    MapPixels pixels;
    const OccupancyGrid g =
        LoadOccupancyGrid(Write("m.yaml", yaml), LimitsConfig{}.max_map_image_pixels, &pixels);
    ASSERT_EQ(g.cols, 3);
    EXPECT_EQ(g.At(0, 0), OccupancyGrid::kOccupied) << c.pgm.substr(0, 12);
    EXPECT_EQ(g.At(0, 1), OccupancyGrid::kFree) << c.pgm.substr(0, 12);
    EXPECT_NEAR(pixels.grey[1] / pixels.max_value, 1.0, 1e-12);
  }
}

TEST(SeedLabMapTest, LoadsTheRoomWithItsOrigin) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const OccupancyGrid g = LoadOccupancyGrid(testing::SeedLabLidarMap());
  EXPECT_EQ(g.cols, 320);
  EXPECT_EQ(g.rows, 82);
  EXPECT_DOUBLE_EQ(g.origin.x_m, -4.82);
  EXPECT_DOUBLE_EQ(g.origin.y_m, -2.07);
  int occupied = 0;
  for (std::int8_t v : g.cells) occupied += v == OccupancyGrid::kOccupied;
  EXPECT_EQ(occupied, 1276);  // the PGM's 0-valued pixels
  int row = 0, col = 0;
  ASSERT_TRUE(g.CellOf({0.0, 0.0}, &row, &col));  // the run's start is free space
  EXPECT_TRUE(g.IsFree(row, col));
  // The room's long walls bound y = 0 on both sides within 2 m.
  auto wall_along_y = [&](double x, double direction) {
    for (double y = 0.0; std::abs(y) < 2.0; y += direction * 0.05) {
      if (g.CellOf({x, y}, &row, &col) && g.IsOccupied(row, col)) return y;
    }
    return 99.0;
  };
  EXPECT_NEAR(wall_along_y(3.0, 1.0), 1.6, 0.1);
  EXPECT_NEAR(wall_along_y(3.0, -1.0), -1.8, 0.1);
}

}  // namespace
}  // namespace uwbsar
