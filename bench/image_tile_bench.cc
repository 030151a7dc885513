// Keyframe tiles imaged by each imaging.method, in one program and one run, so the two are
// timed on the same machine state: BM_ImageTile/direct and BM_ImageTile/ffbp on
//  - sim: the reference geometry (two LT102 radars, 5 mm pixels, 0.4-3 m, +-30 deg), a 4 m
//    straight pass at 0.2 m/s and 100 scans/s per radar past a wall and point targets;
//  - rail: a real PulsON 440 rail log (../shared/data/real/pulson440_rail, rail_sar2.log,
//    coherent, 1 cm pixels as its test images it; skipped with a line when the data is missing).
// Each iteration images every gated scan of the run into tiles (KeyframeBuilder) from range
// profiles made once. Counters: ms per scan pair amortised (per scan for the one-radar rail),
// and the image error of ffbp against direct, worst tile, measured outside the timed loop:
//  - worst_tile_ncc: NCC of the detected (positive, blurred) tiles, led by the bright returns;
//  - worst_feature_ncc: NCC of the 8-bit feature images place recognition detects on (contrast
//    stretched to the 99.5th percentile, so weak returns weigh in);
//  - worst_db_ncc: NCC of the detected tiles in decibels, down to 60 dB below the peak (the
//    weak returns and sidelobes alone).
// In paper mode the last two are well below the first (0.963 and 0.907 against 0.993 on the
// sim): direct interpolates the real RF samples linearly, at 3.2 samples per carrier cycle,
// which adds an image of the echo near fs - fc that ffbp's baseband model does not reproduce
// (coherent mode: 0.994, 0.989, 0.999). See docs/measurements.md, "Imaging".
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <opencv2/core.hpp>

#include "app/app_config_io.h"
#include "drivers/logs/log_source.h"
#include "drivers/logs/text_log.h"
#include "drivers/sim/synthetic_run.h"
#include "frontend/imaging_frontend.h"
#include "frontend/place_recognition/features.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "imaging/enhance.h"
#include "slam/app_config.h"
#include "test/imaging/image_ncc.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

struct Workload {
  Config config;
  std::vector<SensorGeometry> sensors;
  std::vector<ImagedScan> scans;  ///< gated, with their range profiles
  int radars = 2;
};

Workload Gate(Config config, const std::vector<OdometrySample>& odometry,
              const std::vector<RadarScan>& radar_scans) {
  Workload w;
  w.config = config;
  config.imaging.method = ImagingMethod::kFfbp;  // profiles with their quadrature, for both
  w.radars = static_cast<int>(config.radars.size());
  ImagingFrontend frontend{ImagingFrontendConfig(config)};
  frontend.SetScanObserver([&](const ImagedScan& s) { w.scans.push_back(s); });
  LogSource(odometry, radar_scans).Run([&](const Message& m) { FeedScanOrOdometry(frontend, m); });
  frontend.Finish();
  w.sensors = frontend.sensors();
  return w;
}

const Workload& SimWorkload() {
  static const Workload w = [] {
    Config config;
    SyntheticPath path;
    path.length_m = 4.0;
    std::vector<Scatterer> scene = WallScatterers({-0.5, 2.2}, {5.0, 2.2}, 0.01, 0.05);
    for (int i = 0; i < 10; ++i) scene.push_back({{0.45 * i, i % 2 ? -1.2 : 0.9}, 1.0});
    const SyntheticRun run = SimulateRun(config, path, scene, EchoModel{}, 3);
    return Gate(config, run.odometry, run.scans);
  }();
  return w;
}

const Workload* RailWorkload(std::string* missing) {
  *missing = testing::MissingSharedData("real/pulson440_rail/rail_sar2.log");
  if (!missing->empty()) return nullptr;
  static const Workload w = [] {
    Config config =  // the file lists its one radar as the whole list
        LoadConfigs({std::string(UWBSAR_SOURCE_DIR) + "/config/without_default_radars.yaml",
                     testing::SharedDataPath("real/pulson440_rail/p440_team5.yaml")});
    config.imaging.mode = ImagingMode::kCoherent;
    config.imaging.pixel_size_m = 0.01;
    const TextLog log = ReadTextLog(testing::SharedDataPath("real/pulson440_rail/rail_sar2.log"));
    return Gate(config, log.odometry, log.scans);
  }();
  return &w;
}

std::vector<Keyframe> ImageTiles(const Workload& w, ImagingMethod method) {
  ImagingConfig imaging = w.config.imaging;
  imaging.method = method;
  KeyframeBuilder builder(w.config.keyframe, imaging, w.config.pulse, w.sensors);
  for (const ImagedScan& s : w.scans) builder.Add(s);
  builder.Finish();
  return builder.TakeClosed();
}

/// The detected tile features are made from (enhance: positive image or magnitude, blurred).
cv::Mat Detected(const cv::Mat& sar, const EnhanceConfig& enhance) {
  return EnhancedFloat(sar, enhance);
}

void BM_ImageTile(benchmark::State& state, ImagingMethod method, bool rail) {
  std::string missing;
  const Workload* w = rail ? RailWorkload(&missing) : &SimWorkload();
  if (w == nullptr) {
    state.SkipWithError(missing.c_str());
    return;
  }
  cv::setNumThreads(w->config.imaging.num_threads);
  for (auto _ : state) {
    std::vector<Keyframe> tiles = ImageTiles(*w, method);
    benchmark::DoNotOptimize(tiles.data());
  }
  const double units = static_cast<double>(w->scans.size()) / (rail ? 1.0 : w->radars);
  state.counters[rail ? "ms_per_scan" : "ms_per_scan_pair"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * units * 1e-3,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  if (method == ImagingMethod::kFfbp) {
    const std::vector<Keyframe> direct = ImageTiles(*w, ImagingMethod::kDirect);
    const std::vector<Keyframe> ffbp = ImageTiles(*w, ImagingMethod::kFfbp);
    double worst = 1.0, worst_feature = 1.0, worst_db = 1.0;
    const PlaceRecognizerConfig pr(w->config);
    const DetectorConfig& d = pr.place_recognition.detectors;
    const auto feature_image = [&](const cv::Mat& sar) {
      return DownsampleFeatureImage(MakeFeatureImage(sar, pr.enhance, d.mask_erode_px),
                                    pr.feature_downsampling, d.white_percentile);
    };
    const auto db = [&](const cv::Mat& sar) {
      cv::Mat e = Detected(sar, w->config.enhance), out;
      double top = 0.0;
      cv::minMaxLoc(e, nullptr, &top);
      cv::log(cv::max(e, top * 1e-3), out);  // 60 dB below the peak and up
      return out;
    };
    for (std::size_t i = 0; i < direct.size() && i < ffbp.size(); ++i) {
      worst = std::min(worst, ZeroMeanNcc(Detected(direct[i].image, w->config.enhance),
                                          Detected(ffbp[i].image, w->config.enhance)));
      cv::Mat a, b;
      feature_image(direct[i].image).gray.convertTo(a, CV_32F);
      feature_image(ffbp[i].image).gray.convertTo(b, CV_32F);
      worst_feature = std::min(worst_feature, ZeroMeanNcc(a, b));
      worst_db = std::min(worst_db, ZeroMeanNcc(db(direct[i].image), db(ffbp[i].image)));
    }
    state.counters["worst_tile_ncc"] = worst;
    state.counters["worst_feature_ncc"] = worst_feature;
    state.counters["worst_db_ncc"] = worst_db;
  }
  state.SetLabel(std::string(rail ? "PulsON 440 rail_sar2" : "reference geometry") + ", " +
                 std::to_string(w->scans.size()) + " scans, " +
                 std::to_string(w->config.imaging.num_threads) + " thread(s)");
}
BENCHMARK_CAPTURE(BM_ImageTile, direct, ImagingMethod::kDirect, false)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ImageTile, ffbp, ImagingMethod::kFfbp, false)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ImageTile, direct_rail, ImagingMethod::kDirect, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ImageTile, ffbp_rail, ImagingMethod::kFfbp, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace uwbsar
