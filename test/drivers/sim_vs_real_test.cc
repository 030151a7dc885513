// The simulator against reality: the paper's departing run (7 m along
// +x) simulated through the seed_lab LiDAR map, imaged onto the grid of the paper's real
// departing strip (`real/seed_corridor/departing.png`: 7 m x 6 m at
// 5 mm, column 0 = x 0, row 0 = y +3 m) with the paper's enhancement (positive image, blur
// sigma 2 px, min-max to 8 bit over the strip), and compared with it figure by figure:
// The real strip is in the robot's odometry frame at its start; where that start lies in the
// LiDAR map is what `uwbsar compare` measures for the real strip (ICP, docs/real-data.md "The real
// map against LiDAR": T_lidar_sar = (0.182 m, 0 m, 2.19 deg)). The simulated run starts there and
// is imaged in its own start frame, as the real one was.
//  - wall ridges: the row of largest mean intensity (mean over all columns) in the upper
//    and in the lower half, as y in metres;
//  - blind band: the rows around the path (row 600) whose mean stays below 1 % of the
//    image's largest row mean;
//  - the look: wall-to-clutter ratio (mean on the wall bands, +-5 cm about each ridge, over
//    the mean of the room's interior between the blind band and the wall bands), speckle
//    contrast (std / mean) on walls and in clutter, the fraction of pixels above 128, and
//    the normalised cross-correlation of the two 8-bit images.
// With UWBSAR_SIM_VS_REAL_OUT=DIR the test writes DIR/sim_departing.png (ours) and
// DIR/sim_vs_real.png (real on top, simulated below; outside data: never commit it);
// UWBSAR_SIM_VS_REAL_CONFIG=FILE measures another configuration (simulator calibration).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "app/app_config_io.h"
#include "drivers/sim/sim_stream.h"
#include "frontend/imaging_frontend.h"
#include "frontend/strip_renderer.h"
#include "imaging/enhance.h"
#include "imaging/image_io.h"
#include "test/drivers/sim_test_util.h"
#include "test/imaging/image_ncc.h"

namespace uwbsar::sim {
namespace {

constexpr char kDeparting[] = "real/seed_corridor/departing.png";
constexpr int kRows = 1200, kCols = 1400, kPathRow = 600;
constexpr double kResolutionM = 0.005, kTopYm = 3.0;

/// The real run's start in the LiDAR map: T_lidar_sar of `uwbsar compare` on the real strip.
const Pose2 kStartInMap{0.182, 0.0, 2.19 * M_PI / 180.0};

double RowToY(double row) { return kTopYm - row * kResolutionM; }

struct LookFigures {
  int upper_ridge_row = 0, lower_ridge_row = 0;
  int blind_first_row = 0, blind_last_row = 0;  ///< inclusive
  double wall_to_clutter = 0.0;
  double wall_contrast = 0.0, clutter_contrast = 0.0;  ///< std / mean
  double bright_fraction = 0.0;                        ///< pixels > 128
  double upper_y_m() const { return RowToY(upper_ridge_row); }
  double lower_y_m() const { return RowToY(lower_ridge_row); }
};

/// Mean and std / mean of the pixels of `image` where `mask` is set.
void MaskStats(const cv::Mat& image, const cv::Mat& mask, double* mean, double* contrast) {
  cv::Scalar m, s;
  cv::meanStdDev(image, m, s, mask);
  *mean = m[0];
  *contrast = m[0] > 0 ? s[0] / m[0] : 0.0;
}

LookFigures Measure(const cv::Mat& image8u) {
  LookFigures f;
  cv::Mat row_mean;
  cv::reduce(image8u, row_mean, 1, cv::REDUCE_AVG, CV_64F);
  auto argmax = [&](int first, int last) {
    int best = first;
    for (int r = first; r < last; ++r)
      if (row_mean.at<double>(r) > row_mean.at<double>(best)) best = r;
    return best;
  };
  f.upper_ridge_row = argmax(0, kPathRow);
  f.lower_ridge_row = argmax(kPathRow, kRows);
  double peak = 0.0;
  cv::minMaxLoc(row_mean, nullptr, &peak);
  const double dark = 0.01 * peak;
  f.blind_first_row = f.blind_last_row = kPathRow;
  while (f.blind_first_row > 0 && row_mean.at<double>(f.blind_first_row - 1) < dark)
    --f.blind_first_row;
  while (f.blind_last_row + 1 < kRows && row_mean.at<double>(f.blind_last_row + 1) < dark)
    ++f.blind_last_row;

  const int band = static_cast<int>(std::lround(0.05 / kResolutionM));
  cv::Mat wall(image8u.size(), CV_8U, cv::Scalar(0)), clutter = wall.clone();
  for (int ridge : {f.upper_ridge_row, f.lower_ridge_row})
    wall.rowRange(std::max(0, ridge - band), std::min(kRows, ridge + band + 1)).setTo(255);
  if (f.upper_ridge_row + 2 * band < f.blind_first_row)
    clutter.rowRange(f.upper_ridge_row + 2 * band, f.blind_first_row).setTo(255);
  if (f.blind_last_row + 1 < f.lower_ridge_row - 2 * band)
    clutter.rowRange(f.blind_last_row + 1, f.lower_ridge_row - 2 * band).setTo(255);
  double wall_mean = 0.0, clutter_mean = 0.0;
  MaskStats(image8u, wall, &wall_mean, &f.wall_contrast);
  MaskStats(image8u, clutter, &clutter_mean, &f.clutter_contrast);
  f.wall_to_clutter = clutter_mean > 0 ? wall_mean / clutter_mean : 0.0;
  f.bright_fraction =
      static_cast<double>(cv::countNonZero(image8u > 128)) / static_cast<double>(image8u.total());
  return f;
}

void Print(const char* name, const LookFigures& f) {
  std::printf(
      "%-9s ridges y %+.3f / %+.3f m (rows %d / %d), blind rows %d..%d (y %+.2f..%+.2f m), "
      "wall/clutter %.2f, contrast wall %.2f clutter %.2f, bright %.4f\n",
      name, f.upper_y_m(), f.lower_y_m(), f.upper_ridge_row, f.lower_ridge_row, f.blind_first_row,
      f.blind_last_row, RowToY(f.blind_first_row), RowToY(f.blind_last_row), f.wall_to_clutter,
      f.wall_contrast, f.clutter_contrast, f.bright_fraction);
}

/// The departing half of a simulated seed_lab depart-return run, imaged with the wheel
/// odometry poses (as the paper formed its strip) onto the real strip's grid, enhanced.
cv::Mat SimulatedDeparting() {
  const char* config_file = std::getenv("UWBSAR_SIM_VS_REAL_CONFIG");
  const bool own_file = config_file != nullptr && *config_file != '\0';
  Config config = own_file ? LoadConfig(config_file) : Config{};
  // The simulator's look was calibrated against this strip with wheel-only odometry, the
  // premise above; the kobuki_gyro default (issue 32) came later. Under it this seed's gyro
  // bias moves the strip's upper ridge 0.43 m and smears the walls (contrast 1.31).
  if (!own_file) config.simulator.odometry.profile = "wheel";
  config.simulator.route.depart_distance_m = 7.0;  // the paper's strip: 7 m along +x
  config.simulator.route.start_x_m = kStartInMap.x_m;
  config.simulator.route.start_y_m = kStartInMap.y_m;
  config.simulator.route.start_yaw_deg = kStartInMap.yaw_rad * 180.0 / M_PI;
  const SimScenario scenario =
      MakeScenario(config, testing::SeedLabMap(), "depart-return", /*seed=*/1);
  SimStream stream(config, scenario, 1);
  ImagingFrontend frontend(config);
  std::vector<ImagedScan> imaged;
  frontend.SetScanObserver([&](const ImagedScan& s) { imaged.push_back(s); });
  // Messages come in time order; the departing half ends where the robot starts to turn.
  SimMessage msg;
  while (stream.Next(&msg)) {
    if (msg.kind == SimMessage::Kind::kGroundTruth &&
        std::abs(msg.pose.T_world_robot.yaw_rad) > 0.05)
      break;
    if (msg.kind == SimMessage::Kind::kOdometry) frontend.AddOdometry(msg.pose);
    if (msg.kind == SimMessage::Kind::kRadarScan) frontend.AddScan(msg.scan);
  }
  frontend.Finish();
  ImageGrid grid;
  grid.x0_m = 0.0;
  grid.y0_m = kTopYm;
  grid.resolution_m = kResolutionM;
  grid.rows = kRows;
  grid.cols = kCols;
  const Pose2 T_start_world = kStartInMap.Inverse();
  const StripImage strip =
      RenderScans(imaged, frontend.sensors(), grid, false, config.imaging.num_threads,
                  [&](const ImagedScan& s) { return T_start_world * s.T_world_robot; });
  return Enhance8U(strip.image, config.enhance);
}

class SimVsReal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!::uwbsar::testing::MissingSharedData(kDeparting).empty() ||
        !::uwbsar::testing::MissingSharedData("maps/seed_lab/my_map.yaml").empty())
      return;
    real_ = new cv::Mat(
        cv::imread(::uwbsar::testing::SharedDataPath(kDeparting), cv::IMREAD_GRAYSCALE));
    sim_ = new cv::Mat(SimulatedDeparting());
    const char* out = std::getenv("UWBSAR_SIM_VS_REAL_OUT");
    if (out != nullptr && *out != '\0') {
      WriteImageAtomic(std::string(out) + "/sim_departing.png", *sim_);
      cv::Mat both;
      const cv::Mat gap(8, kCols, CV_8U, cv::Scalar(128));  // a gray bar between the two
      cv::vconcat(std::vector<cv::Mat>{*real_, gap, *sim_}, both);
      WriteImageAtomic(std::string(out) + "/sim_vs_real.png", both);
    }
  }
  static void TearDownTestSuite() {
    delete real_;
    delete sim_;
    real_ = sim_ = nullptr;
  }
  void SetUp() override {
    UWBSAR_NEED_SHARED_DATA(kDeparting);
    UWBSAR_NEED_SEED_LAB_MAP();
    ASSERT_EQ(real_->rows, kRows);
    ASSERT_EQ(real_->cols, kCols);
  }
  static cv::Mat* real_;
  static cv::Mat* sim_;
};
cv::Mat* SimVsReal::real_ = nullptr;
cv::Mat* SimVsReal::sim_ = nullptr;

TEST_F(SimVsReal, FiguresOfBothImages) {
  const LookFigures real = Measure(*real_), sim = Measure(*sim_);
  const double ncc = ZeroMeanNcc(*real_, *sim_);
  Print("real", real);
  Print("simulated", sim);
  std::printf("NCC of the two enhanced images: %.3f\n", ncc);

  // The real strip's own figures (outside data: guards the measure itself).
  EXPECT_NEAR(real.upper_y_m(), 1.525, 0.01);
  EXPECT_NEAR(real.lower_y_m(), -1.890, 0.01);
  EXPECT_NEAR(RowToY(real.blind_first_row), 0.34, 0.02);
  EXPECT_NEAR(RowToY(real.blind_last_row), -0.52, 0.02);

  // Walls where the real ones are.
  EXPECT_NEAR(sim.upper_y_m(), real.upper_y_m(), 0.05);
  EXPECT_NEAR(sim.lower_y_m(), real.lower_y_m(), 0.05);
  // The blind band: the imaging's 0.4 m minimum range either side of the antennas, filled up
  // to its edge by the noise floor; the real one reaches 0.2 m closer on the left. With the
  // old simulator noise (0.005) the near ranges stayed black: +0.71 .. -0.82 m.
  EXPECT_LE(sim.blind_first_row, kPathRow);
  EXPECT_GE(sim.blind_last_row, kPathRow);
  EXPECT_NEAR(RowToY(sim.blind_first_row), RowToY(real.blind_first_row), 0.25);  // +0.55 m
  EXPECT_NEAR(RowToY(sim.blind_last_row), RowToY(real.blind_last_row), 0.05);    // -0.50 m

  // The look, with the calibrated simulator defaults (noise_std 0.02; before, with 0.005:
  // wall/clutter 2.91, wall contrast 0.96, clutter contrast 2.32, bright 0.0012, NCC 0.488).
  // The simulated walls stay more speckled than the real ones (each 5 cm cell draws one
  // exponential RCS) and fewer pixels are bright (a few point targets and corners take
  // the top of the 8-bit range); see docs/real-data.md.
  EXPECT_GT(sim.wall_to_clutter, 3.1);  // 3.34, real 4.80
  EXPECT_LT(sim.wall_to_clutter, real.wall_to_clutter);
  EXPECT_GT(sim.wall_contrast, real.wall_contrast);  // 0.94, real 0.55
  EXPECT_LT(sim.wall_contrast, 1.0);
  EXPECT_GT(sim.clutter_contrast, real.clutter_contrast);  // 2.33, real 1.62
  EXPECT_LT(sim.clutter_contrast, 2.45);
  EXPECT_GT(sim.bright_fraction, 0.0006);  // 0.0012, real 0.0057
  EXPECT_LT(sim.bright_fraction, real.bright_fraction);
  EXPECT_GT(ncc, 0.45);  // 0.484
}

}  // namespace
}  // namespace uwbsar::sim
