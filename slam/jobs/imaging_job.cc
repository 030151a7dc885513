#include "slam/jobs/imaging_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <opencv2/core.hpp>
#include <sstream>

#include "core/errors.h"
#include "drivers/logs/log_source.h"
#include "drivers/logs/text_log.h"
#include "imaging/enhance.h"
#include "imaging/image_io.h"
#include "slam/app_config.h"

namespace uwbsar::slam {
namespace {

/// The configuration key that decides the most rejections, as the end of the message of a
/// run with nothing imaged ("" when none stands out): a log recorded with another radar
/// needs that radar's configuration.
std::string FittingKey(const FrontendStats& s) {
  const long long most =
      std::max({s.scans_rejected_length, s.scans_rejected_unknown_sensor,
                s.scans_rejected_no_odometry + s.scans_rejected_stale, s.scans_gated});
  if (most == 0) return {};
  if (most == s.scans_rejected_length) {
    return "; the scans' sample count differs from radars[].num_samples: give the radar's "
           "configuration (--config)";
  }
  if (most == s.scans_rejected_unknown_sensor) {
    return "; the scans come from radars the configuration does not list (radars[])";
  }
  if (most == s.scans_gated) return "; the robot never moved gating.min_travel_m";
  return "; no odometry covers the scans' stamps (gating.max_scan_latency_s)";
}

/// A strip needs imaged scans, and scans that are not all zero (InputError otherwise).
void CheckImaged(const FrontendStats& s) {
  if (s.scans_received == 0) throw InputError("nothing to image: no scans");
  if (s.all_valid_scans_zero()) {
    throw InputError("nothing imaged: every radar scan is zero (" +
                     std::to_string(s.scans_valid()) + " scans)");
  }
  if (s.scans_imaged > 0) return;
  throw InputError("nothing imaged: none of the " + std::to_string(s.scans_received) +
                   " scans could be imaged (" + std::to_string(s.scans_rejected()) + " rejected, " +
                   std::to_string(s.scans_gated) + " while not moving)" + s.BadSamplesNote() +
                   FittingKey(s));
}

}  // namespace

ImagingInput ReadImagingLog(const std::string& path, double max_mb) {
  TextLog log = ReadTextLog(path, max_mb);
  // An empty log used to give a 1 x 1 strip and exit 0.
  if (log.scans.empty()) {
    throw InputError(path + ": no scans (no 'scan' records): nothing to image");
  }
  if (log.odometry.empty()) {
    throw InputError(path + ": no odometry ('odom' records): scans cannot be placed");
  }
  return {std::move(log.odometry), std::move(log.scans)};
}

ImagingInput SyntheticImagingRun(const Config& config, const std::string& scene) {
  if (scene != "straight" && scene != "arc") {
    throw InputError("unknown synthetic scene '" + scene + "' (straight or arc)");
  }
  SyntheticPath path;
  if (scene == "arc") path.turn_radius_m = 4.0;
  SyntheticRun run = SimulateRun(config, path, DemoScatterers(), EchoModel{}, 1);
  return {std::move(run.odometry), std::move(run.scans)};
}

StripResult ImageRun(const Config& config, const std::vector<OdometrySample>& odometry,
                     const std::vector<RadarScan>& scans) {
  const auto start = std::chrono::steady_clock::now();
  StripResult result;
  ImagingFrontend frontend(config);
  frontend.SetScanObserver([&](const ImagedScan& s) { result.scans.push_back(s); });
  LogSource(odometry, scans).Run([&](const Message& m) { FeedScanOrOdometry(frontend, m); });
  frontend.Finish();
  frontend.TakeKeyframes();
  result.stats = frontend.stats();
  CheckImaged(result.stats);
  std::vector<Pose2> poses;
  for (const ImagedScan& s : result.scans) poses.push_back(s.T_world_robot);
  const ImageGrid grid =
      WorldGridCovering(poses, frontend.sensors(), 0.1, config.imaging.pixel_size_m);
  CheckWholeRunImage(grid, config.limits, "the strip image");
  result.strip = RenderScans(result.scans, frontend.sensors(), grid, config.imaging, config.pulse);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<std::string> WriteStripOutputs(const std::string& dir, const std::string& prefix,
                                           const StripImage& strip, const EnhanceConfig& enhance) {
  std::vector<std::string> written;
  auto path = [&](const std::string& suffix) { return dir + "/" + prefix + suffix; };
  auto write = [&](const std::string& suffix, const cv::Mat& image) {
    WriteImageAtomic(path(suffix), image);
    written.push_back(path(suffix));
  };
  const bool coherent = strip.image.channels() == 2;
  // The paper's "initial SAR image": signed values, 0 maps to mid-gray.
  cv::Mat real = strip.image;
  if (coherent) cv::extractChannel(strip.image, real, 0);
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(real, &lo, &hi);
  const double span = std::max(std::abs(lo), std::abs(hi));
  cv::Mat raw8;
  real.convertTo(raw8, CV_8U, span > 0 ? 127.5 / span : 0.0, 127.5);
  write("_raw.png", raw8);
  cv::Mat positive8;
  cv::normalize(PositiveImage(strip.image), positive8, 0, 255, cv::NORM_MINMAX, CV_8U);
  write("_positive.png", positive8);
  write("_enhanced.png", Colorize(Enhance8U(strip.image, enhance), enhance.colormap));
  if (coherent) {
    write("_logmag.png",
          Colorize(LogMagnitude8U(strip.image, enhance.display_range_db), enhance.colormap));
  }
  WriteFloatTiff(path("_float.tif"), strip.image);
  written.push_back(path("_float.tif"));
  std::ostringstream yaml;
  yaml.precision(10);
  yaml << "# Pixel geometry of " << prefix << "_float.tif: column = +x, row = -y (world frame)\n"
       << "image: " << prefix << "_float.tif\n"
       << "x0_m: " << strip.grid.x0_m << "  # x of the centre of column 0\n"
       << "y0_m: " << strip.grid.y0_m << "  # y of the centre of row 0 (top row)\n"
       << "resolution_m: " << strip.grid.resolution_m << "\n"
       << "rows: " << strip.grid.rows << "\ncols: " << strip.grid.cols << "\n"
       << "mode: " << (coherent ? "coherent" : "paper") << "\n";
  WriteTextAtomic(path("_grid.yaml"), yaml.str());
  written.push_back(path("_grid.yaml"));
  return written;
}

std::vector<Point2> DemoPointTargets() {
  return {{0.8, 1.0}, {1.5, 2.0}, {2.2, 1.2}, {0.9, -1.2}, {1.6, -0.8}, {2.3, -2.2}};
}

std::vector<Scatterer> DemoScatterers() {
  std::vector<Scatterer> scene = WallScatterers({-1.0, 2.6}, {4.0, 2.6}, 0.002, 0.05);
  for (const Point2& p : DemoPointTargets()) scene.push_back({p, 1.0});
  return scene;
}

}  // namespace uwbsar::slam
