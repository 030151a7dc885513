#include "slam/outputs/map_outputs.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "backend/g2o_io.h"
#include "backend/global_map.h"
#include "backend/incremental_mosaic.h"
#include "backend/occupancy_io.h"
#include "core/commit_journal.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/shortest_number.h"
#include "frontend/strip_renderer.h"
#include "imaging/enhance.h"
#include "imaging/image_io.h"
#include "slam/app_config.h"
#include "slam/outputs/map_figure.h"
#include "slam/outputs/map_report.h"
#include "slam/outputs/navigation_map.h"
#include "slam/outputs/report_html.h"
#include "slam/outputs/results_timeline.h"
#include "slam/outputs/summary_json.h"

namespace uwbsar::slam {
namespace fs = std::filesystem;
namespace {

std::vector<std::pair<double, Pose2>> InSeconds(
    const std::vector<std::pair<TimestampNs, Pose2>>& trajectory) {
  std::vector<std::pair<double, Pose2>> out;
  out.reserve(trajectory.size());
  for (const auto& [t, p] : trajectory) out.push_back({NsToSeconds(t), p});
  return out;
}

/// map.png: the bare raster (ScaledMapImage) under the odometry (vermillion), the optimised
/// trajectory (sky blue) and, above both, the accepted loops (yellow); FigurePalette's
/// colours, so that map.png and the report's figure agree. Its pixels stay on map_grid.yaml's
/// grid: the axes, legend and colour bar are in the report's figure only.
cv::Mat RenderMapPng(const cv::Mat& raster, const ImageGrid& grid, const SlamSnapshot& slam,
                     const std::vector<std::pair<TimestampNs, Pose2>>& traj) {
  cv::Mat png = raster.clone();
  auto pixel = [&](const Pose2& p) {
    return cv::Point(static_cast<int>(std::lround(grid.XToCol(p.x_m))),
                     static_cast<int>(std::lround(grid.YToRow(p.y_m))));
  };
  const auto& odom = slam.odometry;
  for (std::size_t i = 1; i < odom.size(); ++i) {
    cv::line(png, pixel(odom[i - 1].T_world_robot), pixel(odom[i].T_world_robot),
             FigurePalette::kOdometry.bgr, 1, cv::LINE_AA);
  }
  for (std::size_t i = 1; i < traj.size(); ++i) {
    cv::line(png, pixel(traj[i - 1].second), pixel(traj[i].second), FigurePalette::kSlam.bgr, 2,
             cv::LINE_AA);
  }
  for (const auto& [a, b] : slam.AcceptedLoopSegments()) {
    cv::line(png, pixel(Pose2{a.x_m, a.y_m, 0.0}), pixel(Pose2{b.x_m, b.y_m, 0.0}),
             FigurePalette::kLoop.bgr, 1, cv::LINE_AA);
  }
  return png;
}

std::string LoopsCsv(const SlamSnapshot& slam) {
  std::ostringstream csv;
  // Three columns per detector of the validation pair, named after it (the paper's pair:
  // ratio_akaze,good_akaze,scale_akaze,ratio_orb,good_orb,scale_orb).
  const std::vector<DetectorKind> detectors = slam.LoopDetectors();
  csv << LoopsCsvHeader(detectors) << "\n";
  for (const LoopRecord& l : slam.loops) {
    const Pose2& T = l.validation.constraint.T_ij;
    std::string reason = l.validation.reason;
    for (char& c : reason) {
      if (c == ',' || c == '\n') c = ';';
    }
    csv << l.query_id << "," << l.match_id << ",";
    for (DetectorKind d : detectors) {
      const MatchResult& m = l.Match(d);
      csv << m.ratio_matches << "," << m.good_matches << "," << Fixed(m.scale, 4) << ",";
    }
    csv << (l.validation.accepted ? Fixed(T.x_m, 4) : "") << ","
        << (l.validation.accepted ? Fixed(T.y_m, 4) : "") << ","
        << (l.validation.accepted ? Fixed(T.yaw_rad * 180.0 / M_PI, 3) : "") << ","
        << (l.validation.accepted ? "accepted" : "rejected") << "," << reason << ","
        << (l.validation.accepted ? (l.rejected_by_backend ? "rejected" : "accepted") : "") << ","
        << (l.edge_index >= 0 ? Fixed(l.chi2, 3) : "") << "\n";
  }
  return csv.str();
}

}  // namespace

std::string LoopsCsvHeader(const std::vector<DetectorKind>& detectors) {
  std::string header = "query_id,match_id,";
  for (DetectorKind d : detectors) {
    const std::string n = DetectorColumnName(d);
    header += "ratio_" + n + ",good_" + n + ",scale_" + n + ",";
  }
  return header + "x_m,y_m,yaw_deg,validator,reason,backend,chi2";
}

MapState CaptureMapState(const MapRun& run) {
  MapState state;
  state.slam = run.slam->Capture();
  state.input = run.input;
  state.processing_s = run.processing_s;
  state.log_duration_s = run.log_duration_s();
  state.last_stamp_ns = run.last_stamp_ns;
  state.ground_truth = run.ground_truth;
  return state;
}

namespace {

/// trajectory.tum, odometry.tum, graph.g2o, loops.csv and, with ground truth,
/// ground_truth.tum and the ATEs in `result`. Appends the names written to `names` (but
/// ground_truth.tum, which CommitState lists after report.html, as `files` always had it).
MapTrajectories WriteTrajectories(const MapState& run, const fs::path& stage, MapOutputs* result,
                                  std::vector<std::string>* names) {
  const SlamSnapshot& slam = run.slam;
  auto staged = [&](const char* name) { return (stage / name).string(); };
  MapTrajectories traj;
  traj.slam = slam.CorrectedTrajectory();
  for (const OdometryEntry& e : slam.odometry)
    traj.odometry.push_back({e.stamp_ns, e.T_world_robot});
  WriteTum(staged("trajectory.tum"), InSeconds(traj.slam));
  WriteTum(staged("odometry.tum"), InSeconds(traj.odometry));
  WriteTextAtomic(staged("graph.g2o"), G2oText(slam.poses, slam.edges, slam.fixed_ids));
  WriteTextAtomic(staged("loops.csv"), LoopsCsv(slam));
  names->insert(names->end(), {"trajectory.tum", "odometry.tum", "graph.g2o", "loops.csv"});
  if (!run.ground_truth.empty()) {
    for (const OdometrySample& g : run.ground_truth) {
      traj.ground_truth.push_back({g.stamp_ns, g.T_world_robot});
    }
    WriteTum(staged("ground_truth.tum"), InSeconds(traj.ground_truth));
    result->ate = TrajectoryError(traj.slam, run.ground_truth);
    result->odometry_ate = TrajectoryError(traj.odometry, run.ground_truth);
    if (result->ate.num_poses > 0) {
      // The ATE aligns in the plane, which a straight route allows and evo's 3-D `-a` refuses:
      // the trajectory so aligned lets evo_ape reproduce the ATE without `-a` on any route.
      StampedPoses aligned = traj.slam;
      for (auto& [stamp, pose] : aligned) pose = result->ate.T_reference_estimate * pose;
      WriteTum(staged(kAlignedTrajectoryName), InSeconds(aligned));
    }
  }
  return traj;
}

/// The global map's extent and size, for summary.json.
struct MapExtent {
  SarMosaic mosaic;  ///< the rendered map (results.mcap shows it too)
  ImageGrid grid;
  std::size_t blocks = 0;
  std::size_t memory_bytes = 0;
  cv::Mat raster;  ///< map.png without its paths (for the report's figure)
};

/// The global map from the optimised keyframes: map_float.tif, map_grid.yaml, map.png, and
/// the navigation grid map.yaml + map.pgm.
MapExtent WriteMapAndOccupancy(const MapState& run, const StampedPoses& trajectory,
                               const fs::path& stage, IncrementalMosaic* mosaic,
                               std::vector<std::string>* names) {
  const SlamSnapshot& slam = run.slam;
  const Config& config = *slam.config;
  auto staged = [&](const char* name) { return (stage / name).string(); };
  std::vector<MosaicTile> tiles;
  for (const TileSnapshot& k : slam.tiles) {
    tiles.push_back(
        {k.id, slam.poses.at(k.id), k.detected_grid, [&k] { return k.detected.Load(); }});
  }
  const RenderedGlobalMap global = RenderGlobalMap(
      tiles, config.slam.map_resolution_m, config.limits.max_image_pixels, run.input, mosaic);
  MapExtent extent;
  extent.grid = global.grid;
  const cv::Mat& map = global.map;
  const cv::Mat& observed = global.observed;
  extent.mosaic = {map, observed, extent.grid};
  WriteFloatTiff(staged("map_float.tif"), map);
  WriteTextAtomic(staged("map_grid.yaml"),
                  GridYaml(extent.grid, "map_float.tif and map.png", "map_float.tif"));
  extent.raster = ScaledMapImage(map, observed, config.enhance.colormap);
  WriteImageAtomic(staged("map.png"), RenderMapPng(extent.raster, extent.grid, slam, trajectory));
  // map.pgm is the navigation grid; the paper's intensity rule stays with `compare`, which
  // applies it to map_grid.yaml.
  WriteOccupancyGrid(staged("map.yaml"), "map.pgm", RunNavigationGrid(slam, trajectory));
  names->insert(names->end(), {"map_float.tif", "map_grid.yaml", "map.png", "map.yaml", "map.pgm"});
  extent.blocks = global.blocks;
  extent.memory_bytes = global.memory_bytes;
  return extent;
}

/// The content of summary.json (`ate`, `odometry_ate` from `outputs`).
nlohmann::json SummaryJson(const MapState& run, const MapOutputs& outputs,
                           const MapExtent& extent) {
  const SlamSnapshot& slam = run.slam;
  const LoopCounts counts = CountLoops(slam);
  nlohmann::json s;
  s["input"] = run.input;
  AddCommandWork({run.log_duration_s, run.processing_s, slam.frontend_stats, slam.times, true,
                  slam.num_solves, slam.last_optimization},
                 &s);
  s["keyframes"] = slam.tiles.size();
  s["path_length_m"] = slam.odometry.empty() ? 0.0 : slam.odometry.back().path_m;
  s["loops"] = {{"candidates", slam.loops.size()},
                {"validated", counts.validated},
                {"accepted", counts.accepted},
                {"rejected_by_backend", counts.backend_rejected}};
  // The base calibration the run applied (`uwbsar calibrate`; all 0: uncalibrated), so that a
  // figure says whether it was calibrated.
  s["odometry_calibration"] = OdometryCalibrationJson(slam.config->backend);
  s["map"] = MapExtentJson(extent.grid, extent.blocks, extent.memory_bytes);
  // The shape every map summary shares with a joined one (docs/formats.md): runs[], and the
  // newest run's ATE at the top.
  // keyframes: those the run made, keyframes_kept: those the map holds (a revisit retires views).
  nlohmann::json only_run = {{"id", 0},
                             {"input", run.input},
                             {"keyframes", slam.tiles.size() + slam.retired.size()},
                             {"keyframes_kept", slam.tiles.size()},
                             {"tum", "trajectory.tum"}};
  if (outputs.ate.num_poses > 0) {
    s["ate"] = AteJson(outputs.ate);
    s["odometry_ate"] = AteJson(outputs.odometry_ate);
    only_run["ate"] = s["ate"];
  }
  s["runs"] = nlohmann::json::array({only_run});
  return s;
}

}  // namespace

nlohmann::json AteJson(const AteResult& a) {
  return {{"poses", a.num_poses},
          {"rmse_m", a.rmse_m},
          {"mean_m", a.mean_m},
          {"max_m", a.max_m},
          {"yaw_rmse_deg", a.yaw_rmse_rad * 180.0 / M_PI}};
}

MapOutputs WriteMapFiles(const MapState& run, const std::string& stage_dir,
                         const MapRun* exact_from, IncrementalMosaic* mosaic,
                         std::vector<std::string>* names) {
  MapOutputs result;
  const fs::path stage = stage_dir;
  const MapTrajectories trajectories = WriteTrajectories(run, stage, &result, names);
  const MapExtent extent = WriteMapAndOccupancy(run, trajectories.slam, stage, mosaic, names);
  result.summary = SummaryJson(run, result, extent);
  if (run.slam.config->slam.results_mcap) {
    const auto mcap_start = std::chrono::steady_clock::now();
    WriteRunResultsMcap((stage / kResultsMcapName).string(), run.slam, run.ground_truth,
                        extent.mosaic);
    names->push_back(kResultsMcapName);
    Log(LogLevel::kDebug,
        "stage results.mcap: " +
            ShortestNumber(RoundToDigits(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - mcap_start)
                    .count(),
                3)) +
            " s, " + std::to_string(run.slam.solves.size()) + " solves");
  }
  // report.html shows map.png's raster, framed and annotated (slam/outputs/map_figure.h).
  const std::string figure =
      EncodePng(MapReportFigure(run, trajectories, extent.raster, extent.grid));
  WriteTextAtomic((stage / "report.html").string(),
                  RenderReportHtml(BuildMapReport(run, result, trajectories, figure)));
  names->push_back("report.html");
  // ground_truth.tum is listed here so that MapOutputs::files keeps its order.
  if (!run.ground_truth.empty()) names->push_back("ground_truth.tum");
  if (result.ate.num_poses > 0) names->push_back(kAlignedTrajectoryName);
  if (exact_from != nullptr) {
    for (const std::string& f : WriteExactMap(*exact_from, stage.string())) {
      names->push_back(fs::path(f).filename().string());
    }
  }
  return result;
}

std::vector<std::string> WriteExactMap(const MapRun& run, const std::string& out_dir) {
  const SlamSystem& slam = *run.slam;
  const Config& config = slam.config();
  // Every imaged scan once (consecutive tiles share the scans of their common metre).
  std::vector<ImagedScan> scans;
  std::vector<Pose2> corrected;
  TimestampNs last_stamp = std::numeric_limits<TimestampNs>::min();
  for (const KeyframeRecord& k : slam.keyframes()) {
    for (const ImagedScan& s : k.keyframe.scans) {
      if (!s.profile) {
        throw std::logic_error(
            "the exact map needs the scans' range profiles: map with "
            "slam.keep_scan_profiles: true");
      }
      if (s.stamp_ns < last_stamp ||
          (s.stamp_ns == last_stamp && !scans.empty() && s.sensor_id <= scans.back().sensor_id)) {
        continue;
      }
      last_stamp = s.stamp_ns;
      scans.push_back(s);
      corrected.push_back(slam.CorrectionAt(s.stamp_ns) * s.T_world_robot);
    }
  }
  const ImageGrid grid =
      WorldGridCovering(corrected, slam.sensors(), 0.1, config.imaging.pixel_size_m);
  CheckWholeRunImage(grid, config.limits, "the exact map");
  const StripImage exact =
      RenderScans(scans, slam.sensors(), grid, config.imaging, config.pulse,
                  [&](const ImagedScan& s) { return corrected[&s - scans.data()]; });
  const std::string base = out_dir + "/map_exact";
  WriteFloatTiff(base + "_float.tif", exact.image);
  WriteTextAtomic(base + "_grid.yaml",
                  GridYaml(grid, "map_exact_float.tif and map_exact.png", "map_exact_float.tif"));
  WriteImageAtomic(base + ".png",
                   Colorize(Enhance8U(exact.image, config.enhance), config.enhance.colormap));
  return {base + "_float.tif", base + "_grid.yaml", base + ".png"};
}

std::string GridYaml(const ImageGrid& grid, const std::string& what, const std::string& image,
                     const std::string& frame) {
  std::ostringstream yaml;
  yaml.precision(12);
  yaml << "# Pixel geometry of " << what << ": column = +x, row = -y (" << frame << " frame)\n"
       << "image: " << image << "  # the float map this file describes (uwbsar compare reads it)\n"
       << "x0_m: " << grid.x0_m << "  # x of the centre of column 0\n"
       << "y0_m: " << grid.y0_m << "  # y of the centre of row 0 (top row)\n"
       << "resolution_m: " << grid.resolution_m << "\nrows: " << grid.rows
       << "\ncols: " << grid.cols << "\n";
  return yaml.str();
}

}  // namespace uwbsar::slam
