// Hostile inputs (issue 26): files that used to crash uwbsar, exhaust its memory, end in an
// OpenCV assertion or give a nonsense answer with exit 0. Each is now exit 3 with one line
// naming the file and the field (or, where the input is usable, a result and one warning).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "test/cli_runner.h"
#include "test/shared_data.h"
#include "test/tools/map_test_bag.h"

namespace {

namespace fs = std::filesystem;
using uwbsar::testing::CliRun;
using uwbsar::testing::Uwbsar;

std::string TempDir(const std::string& name) {
  return uwbsar::testing::FreshFolder("uwbsar_hostile", name);
}

const std::string kMap = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";
const char kD1[] = "real/seed_corridor/regions/D1.png";

/// A SAR image of `cols` x `rows` pixels with a few bright dots (a grid YAML's image).
void WriteDotImage(const std::string& path, int cols, int rows) {
  cv::Mat image(rows, cols, CV_8UC1, cv::Scalar(10));
  for (int i = 1; i < 10; ++i) image.at<std::uint8_t>(rows * i / 10, cols * i / 10) = 250;
  cv::imwrite(path, image);
}

// Item 6: `resolution_m: 1e7` segfaulted in MapToOccupancy; 1.0 took 1.6 GB, 2.0 ran out of
// memory. The resolution is range-checked and the occupancy grid it implies is budgeted.
TEST(HostileInputsCliTest, CompareRefusesAGridResolutionAndTheOccupancyGridItImplies) {
  const std::string dir = TempDir("compare");
  WriteDotImage(dir + "/sar.png", 2000, 1000);
  uwbsar::testing::WriteTextFile(dir + "/huge.yaml",
                                 "image: sar.png\nx0_m: 0\ny0_m: 0\nresolution_m: 1e7\n");
  CliRun r = Uwbsar("compare " + dir + "/huge.yaml " + kMap + " --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("huge.yaml:4: grid key 'resolution_m' is 1e+07 m per pixel, outside "
                          "[1e-06, 10]"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  // 1 m per pixel: 2 km x 1 km, 40000 x 20000 cells of 5 cm (8e8), over the 5e7 budget.
  uwbsar::testing::WriteTextFile(dir + "/metre.yaml",
                                 "image: sar.png\nx0_m: 0\ny0_m: 0\nresolution_m: 1.0\n");
  r = Uwbsar("compare " + dir + "/metre.yaml " + kMap + " --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("metre.yaml: grid key 'resolution_m' (1 m x 2000 x 1000 pixels: "
                          "2e+03 x 1e+03 m) implies an occupancy grid of 4e+04 x 2e+04 cells at "
                          "slam.occupancy_resolution_m 0.05 m, more than "
                          "limits.max_map_image_pixels (5e+07)"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

// Item 7: silent radars (every sample 0) or samples of 3e38 ended in "OpenCV Assertion failed
// sar.depth() == CV_32F in WriteFloatTiff", exit 1.
TEST(HostileInputsCliTest, MapRefusesSilentOrOverflowingRadars) {
  const std::string dir = TempDir("silent");
  fs::create_directories(dir + "/zero");
  fs::create_directories(dir + "/big");
  uwbsar::map_test::BagEdits silent;
  silent.radar_sample_value = 0.0f;
  const std::string bag = uwbsar::map_test::WriteRunBag(dir + "/zero", silent);
  CliRun r = Uwbsar("map " + bag + " --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("uwbsar: error: " + bag + ": nothing imaged: every radar scan is zero"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("Assertion"), std::string::npos) << r.output;
  uwbsar::map_test::BagEdits overflowing;
  overflowing.radar_sample_value = 3e38f;
  const std::string big = uwbsar::map_test::WriteRunBag(dir + "/big", overflowing);
  r = Uwbsar("map -q " + big + " --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find(big + ": no radar scan could be imaged"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("; non-finite or overflowing samples, first: radar '"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("(topic /UWBradar"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(": sample 0 is 3e+38"), std::string::npos) << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
}

// `image --log` of an empty log exited 0 with a 1 x 1 strip (item 14).
TEST(HostileInputsCliTest, ImageOfAnEmptyLogIsRefused) {
  const std::string dir = TempDir("empty_log");
  uwbsar::testing::WriteTextFile(dir + "/empty.log", "");
  const CliRun r = Uwbsar("image --log " + dir + "/empty.log --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("empty.log: no scans (no 'scan' records): nothing to image"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out/strip_float.tif"));
}

class HostileCalibrateCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = TempDir("calibrate");
    uwbsar::map_test::BagEdits edits;
    edits.radar = false;  // calibrate reads odometry and truth only
    edits.length_m = 8.0;
    fs::create_directories(dir_ + "/good");
    good_ = uwbsar::map_test::WriteRunBag(dir_ + "/good", edits, dir_ + "/truth.tum");
    edits.odometry_reset_at_s = 8.0;  // 4 m into the run the base restarts from zero
    fs::create_directories(dir_ + "/reset");
    reset_ = uwbsar::map_test::WriteRunBag(dir_ + "/reset", edits);
  }
  static std::string dir_, good_, reset_;
};
std::string HostileCalibrateCliTest::dir_, HostileCalibrateCliTest::good_,
    HostileCalibrateCliTest::reset_;

// Item 10: an odometry reset fitted a scale of -0.337 and wrote a file uwbsar then refused.
TEST_F(HostileCalibrateCliTest, AnOdometryResetIsRefusedAndNothingWritten) {
  const CliRun r = Uwbsar("calibrate " + reset_ + " --ground-truth " + dir_ + "/truth.tum --out " +
                          dir_ + "/reset.yaml");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find(reset_ + ": odometry jumps 3.990 m and 0.000 rad in 0.020 s"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("a reset or two runs in one recording"), std::string::npos) << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir_ + "/reset.yaml"));
}

// Constant ground truth fitted -1.000000 +- 0; truth out of time order was taken as it came.
TEST_F(HostileCalibrateCliTest, GroundTruthThatDoesNotMoveOrGoesBackIsRefused) {
  std::ifstream in(dir_ + "/truth.tum");
  std::vector<double> stamps;
  for (std::string line; std::getline(in, line);) stamps.push_back(std::stod(line));
  std::ofstream still(dir_ + "/still.tum"), back(dir_ + "/back.tum");
  still.precision(17);
  back.precision(17);
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    still << stamps[i] << " 1 2 0 0 0 0 1\n";
    back << stamps[i == 5 ? 6 : i == 6 ? 5 : i] << " 0 0 0 0 0 0 1\n";
  }
  still.close();
  back.close();
  CliRun r = Uwbsar("calibrate " + good_ + " --ground-truth " + dir_ + "/still.tum");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("still.tum: the ground truth does not move: 0.000 m over the 16 "
                          "segments where the odometry travels"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  r = Uwbsar("calibrate " + good_ + " --ground-truth " + dir_ + "/back.tum");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("back.tum: stamps go back at sample 6"), std::string::npos) << r.output;
}

// Issue 45 item 7: a 3 m jump in --ground-truth fitted half the real scale with exit 0. The truth
// is held to the odometry's jump rule; the refusal names the file, the line and the stamp.
TEST_F(HostileCalibrateCliTest, AGroundTruthJumpIsRefusedNamingTheLine) {
  std::ifstream in(dir_ + "/truth.tum");
  std::ofstream jump(dir_ + "/jump.tum");
  jump.precision(17);
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    double v[8];
    for (double& x : v) fields >> x;
    if (++line_no >= 201) v[1] += 3.0;  // the motion capture's origin moved by 3 m
    for (int i = 0; i < 8; ++i) jump << v[i] << (i < 7 ? " " : "\n");
  }
  jump.close();
  const CliRun r = Uwbsar("calibrate " + good_ + " --ground-truth " + dir_ + "/jump.tum --out " +
                          dir_ + "/jump.yaml");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("jump.tum:201: ground truth jumps 3.0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" s (sample 200): a reset"), std::string::npos) << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir_ + "/jump.yaml"));
}

// Issue 45 item 8: a bag in 2150 was mapped with exit 0 and its results.mcap said 2014. Stamps
// the outputs' ROS 2 times cannot hold are refused where they are read, bag or TUM file.
TEST(HostileInputsCliTest, MapRefusesStampsBeyond2038NamingTheMessageOrLine) {
  const std::string dir = TempDir("year_2150");
  fs::create_directories(dir + "/future");
  uwbsar::map_test::BagEdits in_2150;
  in_2150.start_stamp_ns = 5680281600LL * 1000000000LL;  // 2150-01-01
  const std::string future = uwbsar::map_test::WriteRunBag(dir + "/future", in_2150);
  CliRun r = Uwbsar("map " + future + " --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(
      r.output.find(future + "/run_0.db3: message 0 on /odom (nav_msgs/msg/Odometry): "
                             "log time stamp 5680281600.000000000 s (2150-01-01 00:00:00 UTC) is "
                             "outside 1970-01-01 00:00:00 .. 2038-01-19 03:14:07 UTC"),
      std::string::npos)
      << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out/results.mcap"));
  // A TUM ground truth in 2150 would have gone into results.mcap's /ground_truth path.
  const std::string bag = uwbsar::map_test::WriteRunBag(dir, uwbsar::map_test::BagEdits{});
  uwbsar::testing::WriteTextFile(dir + "/truth.tum",
                                 "# t x y z qx qy qz qw\n5680281600 0 0 0 0 0 0 1\n");
  r = Uwbsar("map " + bag + " --ground-truth " + dir + "/truth.tum --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("truth.tum:2: stamp 5680281600 s is outside 1970-01-01 00:00:00 .. "
                          "2038-01-19 03:14:07 UTC"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out/results.mcap"));
}

// -q did not quiet calibrate: it prints only its result, the configuration keys, and nothing
// at all when --out receives them.
TEST_F(HostileCalibrateCliTest, QuietPrintsOnlyTheCalibration) {
  CliRun r = Uwbsar("calibrate -q " + good_ + " --ground-truth " + dir_ + "/truth.tum");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.rfind("# uwbsar calibrate: 16 segments", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("  calibration_scale_mean: 0"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("per-segment error"), std::string::npos) << r.output;
  r = Uwbsar("calibrate -q " + good_ + " --ground-truth " + dir_ + "/truth.tum --out " + dir_ +
             "/q.yaml");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  EXPECT_TRUE(fs::exists(dir_ + "/q.yaml"));
}

// -q did not quiet optimize either.
TEST(HostileInputsCliTest, QuietQuietsOptimize) {
  const std::string dir = TempDir("quiet_optimize");
  uwbsar::testing::WriteTextFile(
      dir + "/graph.g2o",
      "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n");
  CliRun r = Uwbsar("optimize -q " + dir + "/graph.g2o --out " + dir + "/out.g2o");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  EXPECT_TRUE(fs::exists(dir + "/out.g2o"));
  r = Uwbsar("optimize -q " + dir + "/graph.g2o --json");  // what --json exists to print stays
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"termination\""), std::string::npos) << r.output;
}

/// D1 (the paper's departing pass, 8-bit) written as a binary PGM of `maxval`.
void WritePgmOfD1(const std::string& path, int maxval) {
  const cv::Mat d1 = cv::imread(uwbsar::testing::SharedDataPath(kD1), cv::IMREAD_GRAYSCALE);
  std::ofstream out(path, std::ios::binary);
  out << "P5\n" << d1.cols << " " << d1.rows << "\n" << maxval << "\n";
  for (int r = 0; r < d1.rows; ++r) {
    for (int c = 0; c < d1.cols; ++c) {
      const int v = static_cast<int>(std::lround(d1.at<std::uint8_t>(r, c) * maxval / 255.0));
      if (maxval > 255) out.put(static_cast<char>(v >> 8));
      out.put(static_cast<char>(v & 0xff));
    }
  }
}

/// "x %+.3f m" of `match`'s "accepted:" line (NaN when rejected).
double AcceptedX(const std::string& output) {
  const std::size_t at = output.find("accepted: x ");
  return at == std::string::npos ? std::nan("") : std::stod(output.substr(at + 12));
}

// Item 11: 16-bit images were scaled by 255/65535 whatever their range: a maxval-1023 PGM of
// D1 gave a nonsense transform, maxval 300 was "uniform".
TEST(HostileInputsCliTest, MatchScalesSixteenBitImagesByTheirRange) {
  UWBSAR_NEED_SHARED_DATA(kD1);
  const std::string dir = TempDir("match16");
  const std::string r1 = uwbsar::testing::SharedDataPath("real/seed_corridor/regions/R1.png");
  const CliRun eight = Uwbsar("match " + uwbsar::testing::SharedDataPath(kD1) + " " + r1);
  ASSERT_EQ(eight.exit_code, 0) << eight.output;
  ASSERT_FALSE(std::isnan(AcceptedX(eight.output))) << eight.output;
  for (const int maxval : {1023, 300}) {
    const std::string pgm = dir + "/D1_" + std::to_string(maxval) + ".pgm";
    WritePgmOfD1(pgm, maxval);
    const CliRun r = Uwbsar("match " + pgm + " " + r1);
    EXPECT_EQ(r.exit_code, 0) << maxval << ": " << r.output;
    EXPECT_NEAR(AcceptedX(r.output), AcceptedX(eight.output), 0.01) << maxval << ": " << r.output;
  }
}

// A float TIFF with 1/9 NaN pixels gave 0 keypoints without a word; all NaN is refused.
TEST(HostileInputsCliTest, MatchReadsNaNPixelsAsNotMeasuredWithOneWarning) {
  UWBSAR_NEED_SHARED_DATA(kD1);
  const std::string dir = TempDir("match_nan");
  const std::string d1 = uwbsar::testing::SharedDataPath(kD1);
  cv::Mat image;
  cv::imread(d1, cv::IMREAD_GRAYSCALE).convertTo(image, CV_32F);
  int nan = 0;
  for (int i = 0; i < static_cast<int>(image.total()); i += 9, ++nan) {
    image.at<float>(i / image.cols, i % image.cols) = std::nanf("");
  }
  cv::imwrite(dir + "/nan.tif", image);
  const std::string r1 = uwbsar::testing::SharedDataPath("real/seed_corridor/regions/R1.png");
  const CliRun eight = Uwbsar("match " + d1 + " " + r1);
  CliRun r = Uwbsar("match " + dir + "/nan.tif " + r1);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // The scattered holes are dropouts inside the scene: the same loop as the 8-bit D1's.
  EXPECT_NEAR(AcceptedX(r.output), AcceptedX(eight.output), 0.02) << r.output;
  EXPECT_NE(
      r.output.find("nan.tif: " + std::to_string(nan) + " of " + std::to_string(image.total()) +
                    " values are NaN or infinite; read as not measured (0)"),
      std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("keypoints 0 "), std::string::npos) << r.output;
  image.setTo(std::nanf(""));
  cv::imwrite(dir + "/all_nan.tif", image);
  r = Uwbsar("match " + dir + "/all_nan.tif " + d1);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("all_nan.tif: SAR image holds no finite pixel"), std::string::npos)
      << r.output;
}

// Item 14: a symlink loop was exit 1 (a filesystem exception), D2147483648.png exit 1 "stoi".
TEST(HostileInputsCliTest, SymlinkLoopsAndHugeRegionIndicesAreBadInput) {
  const std::string dir = TempDir("links");
  fs::create_symlink("loop.png", dir + "/loop.png");
  WriteDotImage(dir + "/ok.png", 200, 200);
  CliRun r = Uwbsar("match " + dir + "/loop.png " + dir + "/ok.png");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("loop.png: cannot read SAR image: Too many levels of symbolic links"),
            std::string::npos)
      << r.output;
  fs::create_directories(dir + "/regions");
  fs::create_symlink("D1.png", dir + "/regions/D1.png");
  WriteDotImage(dir + "/regions/R1.png", 200, 200);
  r = Uwbsar("loops --images " + dir + "/regions");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("D1.png: cannot read the image: Too many levels of symbolic links"),
            std::string::npos)
      << r.output;
  fs::remove(dir + "/regions/D1.png");
  WriteDotImage(dir + "/regions/D2147483648.png", 200, 200);
  r = Uwbsar("loops --images " + dir + "/regions");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("D2147483648.png: region index '2147483648' is too large"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(uwbsar::testing::LineCount(r.output), 1) << r.output;
}

// --config naming a folder was exit 2 (a command-line error) while /dev/zero was 3.
TEST(HostileInputsCliTest, AConfigThatIsAFolderOrADeviceIsBadInput) {
  const std::string dir = TempDir("config_folder");
  CliRun r = Uwbsar("--config " + dir + " config");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_EQ(r.output, "uwbsar: error: " + dir + ": configuration file is a folder\n");
  r = Uwbsar("--config /dev/zero config");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_EQ(r.output,
            "uwbsar: error: /dev/zero: configuration file is not a regular file (a device)\n");
}

// Item 13: the same YAML reader for every file: a duplicate key in a grid YAML, a second
// document in the configuration, 010 for a number.
TEST(HostileInputsCliTest, DuplicateKeysSecondDocumentsAndLeadingZerosAreRefused) {
  const std::string dir = TempDir("yaml");
  WriteDotImage(dir + "/sar.png", 200, 100);
  uwbsar::testing::WriteTextFile(
      dir + "/dup.yaml",
      "image: sar.png\nx0_m: 0\ny0_m: 0\nresolution_m: 0.01\nresolution_m: 0.02\n");
  CliRun r = Uwbsar("compare " + dir + "/dup.yaml " + kMap + " --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_EQ(r.output, "uwbsar: error: " + dir +
                          "/dup.yaml:5: duplicate key 'resolution_m' (first at line 4)\n");
  uwbsar::testing::WriteTextFile(dir + "/two.yaml",
                                 "imaging:\n  pixel_size_m: 0.005\n---\nimaging:\n  mode: x\n");
  r = Uwbsar("--config " + dir + "/two.yaml config");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_EQ(r.output, "uwbsar: error: " + dir +
                          "/two.yaml:3: a second YAML document (after '---'); a file holds one "
                          "document\n");
  uwbsar::testing::WriteTextFile(dir + "/octal.yaml", "imaging:\n  num_threads: 010\n");
  r = Uwbsar("--config " + dir + "/octal.yaml config");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("octal.yaml:2: 'imaging.num_threads' has value '010' with a leading "
                          "zero"),
            std::string::npos)
      << r.output;
}

}  // namespace
