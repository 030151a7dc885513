// Real raw scans of another impulse radar: three rail-SAR runs of a PulsON 440 (16.384 GS/s,
// ~4 GHz, one right-looking antenna) with motion-capture poses and corner reflectors
// (../shared/data/real/pulson440_rail, with the uwbsar configurations given there). The
// imaging core (matched filter, coherent back-projection) must keep focusing them: the
// strongest pixel near each reflector sits at its expected image position, and it stands
// far above the image's median (a defocused image smears it into the clutter).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "app/app_config_io.h"
#include "drivers/logs/text_log.h"
#include "imaging/enhance.h"
#include "slam/jobs/imaging_job.h"
#include "test/imaging/image_ncc.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

struct Peak {
  Point2 position;
  double value = 0.0;
};

/// The rail run imaged as `uwbsar --config config/without_default_radars.yaml --config CONFIG
/// image --log LOG --mode coherent --resolution 0.01` does (with `method`: imaging.method); |I|
/// of the strip. CONFIG lists its one radar as the whole list, so the default radars go first.
slam::StripResult ImageRail(const std::string& log, const std::string& config_file,
                            ImagingMethod method = ImagingMethod::kDirect) {
  Config config =
      LoadConfigs({std::string(UWBSAR_SOURCE_DIR) + "/config/without_default_radars.yaml",
                   testing::SharedDataPath("real/pulson440_rail/" + config_file)});
  config.imaging.mode = ImagingMode::kCoherent;
  config.imaging.pixel_size_m = 0.01;
  config.imaging.method = method;
  TextLog text = ReadTextLog(testing::SharedDataPath("real/pulson440_rail/" + log));
  return slam::ImageRun(config, text.odometry, text.scans);
}

/// Strongest |I| pixel within radius_m of `expected`.
Peak StrongestNear(const cv::Mat& magnitude, const ImageGrid& grid, Point2 expected,
                   double radius_m) {
  Peak best;
  for (int r = 0; r < magnitude.rows; ++r) {
    for (int c = 0; c < magnitude.cols; ++c) {
      const Point2 p = grid.PixelToMetric(c, r);
      if (std::hypot(p.x_m - expected.x_m, p.y_m - expected.y_m) > radius_m) continue;
      const double v = magnitude.at<float>(r, c);
      if (v > best.value) best = {p, v};
    }
  }
  return best;
}

double MedianOfImaged(const cv::Mat& magnitude) {
  std::vector<float> values;
  for (int r = 0; r < magnitude.rows; ++r) {
    for (int c = 0; c < magnitude.cols; ++c) {
      const float v = magnitude.at<float>(r, c);
      if (v > 0.0f) values.push_back(v);
    }
  }
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

/// Focus of each reflector: position within 15 cm of the expected one and within 3 cm of an
/// independent numpy back-projection of the same log (the data's README), peak-to-median
/// above 10 (a focused corner reflector stands 50-80x above the clutter median; a defocused
/// one smears into it). Returns the peaks.
std::vector<Peak> CheckFocus(const std::string& log, const std::string& config_file,
                             const std::vector<Point2>& expected,
                             const std::vector<Point2>& independent) {
  const slam::StripResult result = ImageRail(log, config_file);
  const cv::Mat magnitude = MagnitudeImage(result.strip.image);
  const double median = MedianOfImaged(magnitude);
  std::vector<Peak> peaks;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const Point2& e = expected[k];
    const Peak p = StrongestNear(magnitude, result.strip.grid, e, 0.5);
    const double error_m = std::hypot(p.position.x_m - e.x_m, p.position.y_m - e.y_m);
    const double independent_m =
        std::hypot(p.position.x_m - independent[k].x_m, p.position.y_m - independent[k].y_m);
    std::printf(
        "%s: reflector expected (%.3f, %.3f), peak (%.3f, %.3f): %.3f m off (%.3f m from "
        "the independent implementation), peak/median %.1f (%lld scans imaged)\n",
        log.c_str(), e.x_m, e.y_m, p.position.x_m, p.position.y_m, error_m, independent_m,
        p.value / median, result.stats.scans_imaged);
    EXPECT_LT(error_m, 0.15) << log;
    EXPECT_LT(independent_m, 0.03) << log;
    EXPECT_GT(p.value / median, 10.0) << log;
    peaks.push_back(p);
  }
  return peaks;
}

TEST(PulsonRailTest, Trial6FocusesBothReflectorsAtTheirDistance) {
  UWBSAR_NEED_SHARED_DATA("real/pulson440_rail/rail_trial6.log");
  const std::vector<Point2> expected = {{2.411, 3.877}, {2.535, -1.034}};
  const std::vector<Point2> independent = {{2.43, 3.96}, {2.46, -1.15}};
  const std::vector<Peak> peaks =
      CheckFocus("rail_trial6.log", "p440_team6.yaml", expected, independent);
  auto distance = [](Point2 a, Point2 b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); };
  const double imaged_m = distance(peaks[0].position, peaks[1].position);
  const double expected_m = distance(expected[0], expected[1]);
  const double independent_m = distance(independent[0], independent[1]);
  std::printf(
      "rail_trial6: reflectors %.3f m apart in the image; %.3f m in the independent "
      "back-projection, %.3f m between the expected positions\n",
      imaged_m, independent_m, expected_m);
  // Both back-projections put the reflectors about 0.2 m farther apart along the rail than
  // the expected positions: the log's radar stamps run about 5 % slow against the motion
  // capture (scaling them by 1.04-1.06 closes the gap), which no imaging setting can fix.
  EXPECT_NEAR(imaged_m, independent_m, 0.10);
  EXPECT_NEAR(imaged_m, expected_m, 0.25);
}

TEST(PulsonRailTest, RailSar2FocusesItsReflector) {
  UWBSAR_NEED_SHARED_DATA("real/pulson440_rail/rail_sar2.log");
  CheckFocus("rail_sar2.log", "p440_team5.yaml", {{-0.662, 1.160}}, {{-0.66, 1.18}});
}

TEST(PulsonRailTest, RailSar3FocusesItsReflector) {
  UWBSAR_NEED_SHARED_DATA("real/pulson440_rail/rail_sar3.log");
  CheckFocus("rail_sar3.log", "p440_team5.yaml", {{-0.662, 1.160}}, {{-0.66, 1.17}});
}

/// imaging.method ffbp against direct on the real rail images: |I| alike (NCC of the detected
/// strips) and every reflector's peak where direct puts it, within 1 cm.
TEST(PulsonRailTest, FactorisedBackProjectionKeepsTheReflectors) {
  struct Run {
    const char* log;
    const char* config;
    std::vector<Point2> reflectors;
  };
  const std::vector<Run> runs = {
      {"rail_trial6.log", "p440_team6.yaml", {{2.411, 3.877}, {2.535, -1.034}}},
      {"rail_sar2.log", "p440_team5.yaml", {{-0.662, 1.160}}},
      {"rail_sar3.log", "p440_team5.yaml", {{-0.662, 1.160}}}};
  for (const Run& run : runs) {
    UWBSAR_NEED_SHARED_DATA(std::string("real/pulson440_rail/") + run.log);
    const slam::StripResult direct = ImageRail(run.log, run.config);
    const slam::StripResult ffbp = ImageRail(run.log, run.config, ImagingMethod::kFfbp);
    ASSERT_EQ(direct.strip.image.size(), ffbp.strip.image.size());
    const EnhanceConfig enhance;
    const double ncc = ZeroMeanNcc(EnhancedFloat(direct.strip.image, enhance),
                                   EnhancedFloat(ffbp.strip.image, enhance));
    const cv::Mat mag_direct = MagnitudeImage(direct.strip.image);
    const cv::Mat mag_ffbp = MagnitudeImage(ffbp.strip.image);
    for (const Point2& e : run.reflectors) {
      const Peak d = StrongestNear(mag_direct, direct.strip.grid, e, 0.5);
      const Peak f = StrongestNear(mag_ffbp, ffbp.strip.grid, e, 0.5);
      const double offset_m =
          std::hypot(d.position.x_m - f.position.x_m, d.position.y_m - f.position.y_m);
      std::printf("%s ffbp: NCC %.4f, reflector peak %.3f m from direct's, level %+.2f dB\n",
                  run.log, ncc, offset_m, 20.0 * std::log10(f.value / d.value));
      EXPECT_LE(offset_m, 0.01) << run.log;
    }
    EXPECT_GE(ncc, 0.99) << run.log;
  }
}

}  // namespace
}  // namespace uwbsar
