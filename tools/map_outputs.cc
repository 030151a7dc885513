#include "tools/map_outputs.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "backend/g2o_io.h"
#include "backend/global_map.h"
#include "backend/occupancy_io.h"
#include "frontend/enhance.h"
#include "frontend/image_io.h"
#include "frontend/strip_renderer.h"
#include "slam/errors.h"
#include "tools/commands.h"
#include "tools/imaging_job.h"
#include "tools/report_html.h"

namespace uwbsar::tools {
namespace fs = std::filesystem;
namespace {

std::string Fixed(double v, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << v;
  return out.str();
}

std::vector<std::pair<double, Pose2>> InSeconds(
    const std::vector<std::pair<TimestampNs, Pose2>>& trajectory) {
  std::vector<std::pair<double, Pose2>> out;
  out.reserve(trajectory.size());
  for (const auto& [t, p] : trajectory) out.push_back({NsToSeconds(t), p});
  return out;
}

/// map.png: the mean detected map, clipped at its 99.5th percentile, colour-mapped,
/// with the optimised trajectory (white), odometry (grey) and accepted loops (cyan).
cv::Mat RenderMapPng(const cv::Mat& map, const cv::Mat& observed, const ImageGrid& grid,
                     const SlamSnapshot& slam,
                     const std::vector<std::pair<TimestampNs, Pose2>>& traj,
                     const std::string& colormap) {
  std::vector<float> values;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      if (observed.at<unsigned char>(r, c)) values.push_back(map.at<float>(r, c));
    }
  }
  float top = 1.0f;
  if (!values.empty()) {
    const std::size_t k = static_cast<std::size_t>(0.995 * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    top = std::max(values[k], 1e-12f);
  }
  cv::Mat gray;
  map.convertTo(gray, CV_8U, 255.0 / top);
  cv::Mat png = Colorize(gray, colormap);
  png.setTo(cv::Scalar(40, 40, 40), ~observed);
  auto pixel = [&](const Pose2& p) {
    return cv::Point(static_cast<int>(std::lround(grid.XToCol(p.x_m))),
                     static_cast<int>(std::lround(grid.YToRow(p.y_m))));
  };
  const auto& odom = slam.odometry;
  for (std::size_t i = 1; i < odom.size(); ++i) {
    cv::line(png, pixel(odom[i - 1].T_world_robot), pixel(odom[i].T_world_robot),
             cv::Scalar(150, 150, 150), 1, cv::LINE_AA);
  }
  for (std::size_t i = 1; i < traj.size(); ++i) {
    cv::line(png, pixel(traj[i - 1].second), pixel(traj[i].second), cv::Scalar(255, 255, 255), 2,
             cv::LINE_AA);
  }
  const auto& poses = slam.poses;
  for (const LoopRecord& loop : slam.loops) {
    if (!loop.accepted()) continue;
    cv::line(png, pixel(poses.at(loop.match_id)), pixel(poses.at(loop.query_id)),
             cv::Scalar(255, 255, 0), 1, cv::LINE_AA);
  }
  return png;
}

std::string LoopsCsv(const SlamSnapshot& slam) {
  std::ostringstream csv;
  csv << "query_id,match_id,ratio_akaze,good_akaze,scale_akaze,ratio_orb,good_orb,scale_orb,"
         "x_m,y_m,yaw_deg,validator,reason,backend,chi2\n";
  for (const LoopRecord& l : slam.loops) {
    const Pose2& T = l.validation.constraint.T_ij;
    std::string reason = l.validation.reason;
    for (char& c : reason) {
      if (c == ',' || c == '\n') c = ';';
    }
    csv << l.query_id << "," << l.match_id << "," << l.akaze.ratio_matches << ","
        << l.akaze.good_matches << "," << Fixed(l.akaze.scale, 4) << "," << l.orb.ratio_matches
        << "," << l.orb.good_matches << "," << Fixed(l.orb.scale, 4) << ","
        << (l.validation.accepted ? Fixed(T.x_m, 4) : "") << ","
        << (l.validation.accepted ? Fixed(T.y_m, 4) : "") << ","
        << (l.validation.accepted ? Fixed(T.yaw_rad * 180.0 / M_PI, 3) : "") << ","
        << (l.validation.accepted ? "accepted" : "rejected") << "," << reason << ","
        << (l.validation.accepted ? (l.rejected_by_backend ? "rejected" : "accepted") : "") << ","
        << (l.edge_index >= 0 ? Fixed(l.chi2, 3) : "") << "\n";
  }
  return csv.str();
}

nlohmann::json AteJson(const AteResult& a) {
  return {{"poses", a.num_poses},
          {"rmse_m", a.rmse_m},
          {"mean_m", a.mean_m},
          {"max_m", a.max_m},
          {"yaw_rmse_deg", a.yaw_rmse_rad * 180.0 / M_PI}};
}

std::string GridYaml(const ImageGrid& grid, const std::string& what, const std::string& image) {
  std::ostringstream yaml;
  yaml.precision(12);
  yaml << "# Pixel geometry of " << what << ": column = +x, row = -y (world frame)\n"
       << "image: " << image << "  # the float map this file describes (uwbsar compare reads it)\n"
       << "x0_m: " << grid.x0_m << "  # x of the centre of column 0\n"
       << "y0_m: " << grid.y0_m << "  # y of the centre of row 0 (top row)\n"
       << "resolution_m: " << grid.resolution_m << "\nrows: " << grid.rows
       << "\ncols: " << grid.cols << "\n";
  return yaml.str();
}

void RemoveOutput(const fs::path& path) {
  std::error_code ec;
  fs::remove(path, ec);
  if (ec) throw std::runtime_error(path.string() + ": cannot remove: " + ec.message());
}

std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

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

MapOutputs MapOutputStage::Commit(const MapRun& run, const MapOutputOptions& options) {
  return CommitState(CaptureMapState(run), options.exact ? &run : nullptr);
}

MapOutputs MapOutputStage::Commit(const MapState& state) { return CommitState(state, nullptr); }

MapOutputs MapOutputStage::CommitState(const MapState& run, const MapRun* exact_from) {
  const SlamSnapshot& slam = run.slam;
  const Config& config = *slam.config;
  const std::string& out_dir = out_dir_;
  MapOutputs result;
  const fs::path stage = stage_;
  auto staged = [&](const char* name) { return (stage / name).string(); };
  {
    // Trajectories.
    const auto trajectory = slam.CorrectedTrajectory();
    std::vector<std::pair<TimestampNs, Pose2>> odometry;
    for (const OdometryEntry& e : slam.odometry) odometry.push_back({e.stamp_ns, e.T_world_robot});
    WriteTum(staged("trajectory.tum"), InSeconds(trajectory));
    WriteTum(staged("odometry.tum"), InSeconds(odometry));
    WriteTextAtomic(staged("graph.g2o"), G2oText(slam.poses, slam.edges, slam.fixed_ids));
    WriteTextAtomic(staged("loops.csv"), LoopsCsv(slam));
    std::vector<std::string> names = {"trajectory.tum", "odometry.tum",  "graph.g2o", "loops.csv",
                                      "map_float.tif",  "map_grid.yaml", "map.png",   "map.yaml",
                                      "map.pgm",        "report.html"};
    if (!run.ground_truth.empty()) {
      std::vector<std::pair<double, Pose2>> gt;
      for (const OdometrySample& g : run.ground_truth)
        gt.push_back({NsToSeconds(g.stamp_ns), g.T_world_robot});
      WriteTum(staged("ground_truth.tum"), gt);
      names.push_back("ground_truth.tum");
      result.ate = TrajectoryError(trajectory, run.ground_truth);
      result.odometry_ate = TrajectoryError(odometry, run.ground_truth);
    }

    // The global map from the optimised keyframes.
    GlobalMap global(config.slam.map_resolution_m);
    const auto& poses = slam.poses;
    for (const TileSnapshot& k : slam.tiles)
      global.AddTile(k.detected, k.detected_grid, poses.at(k.id));
    ImageGrid grid;
    cv::Mat observed;
    const cv::Mat map = global.Render(&grid, &observed);
    WriteFloatTiff(staged("map_float.tif"), map);
    WriteTextAtomic(staged("map_grid.yaml"),
                    GridYaml(grid, "map_float.tif and map.png", "map_float.tif"));
    WriteImageAtomic(staged("map.png"),
                     RenderMapPng(map, observed, grid, slam, trajectory, config.enhance.colormap));
    const OccupancyGrid occupancy =
        MapToOccupancy(map, observed, grid, config.slam.occupancy_resolution_m,
                       config.slam.occupied_fraction, config.slam.occupancy_reference_percentile);
    WriteOccupancyGrid(staged("map.yaml"), "map.pgm", occupancy);

    // Summary.
    const FrontendStats& fs_stats = slam.frontend_stats;
    int validated = 0, accepted = 0, backend_rejected = 0;
    for (const LoopRecord& l : slam.loops) {
      validated += l.validation.accepted;
      accepted += l.accepted();
      backend_rejected += l.validation.accepted && l.rejected_by_backend;
    }
    const double rtf = run.processing_s > 0 ? run.log_duration_s / run.processing_s : 0.0;
    nlohmann::json& s = result.summary;
    s["input"] = run.input;
    s["log_duration_s"] = run.log_duration_s;
    s["processing_s"] = run.processing_s;
    s["real_time_factor"] = rtf;
    s["peak_memory_mib"] = PeakMemoryMiB();
    s["keyframes"] = slam.tiles.size();
    s["path_length_m"] = slam.odometry.empty() ? 0.0 : slam.odometry.back().path_m;
    s["loops"] = {{"candidates", slam.loops.size()},
                  {"validated", validated},
                  {"accepted", accepted},
                  {"rejected_by_backend", backend_rejected}};
    s["scans"] = {{"received", fs_stats.scans_received},
                  {"imaged", fs_stats.scans_imaged},
                  {"gated", fs_stats.scans_gated},
                  {"rejected", fs_stats.scans_rejected()},
                  {"rejected_wrong_length", fs_stats.scans_rejected_length},
                  {"rejected_non_finite", fs_stats.scans_rejected_nonfinite},
                  {"rejected_no_odometry",
                   fs_stats.scans_rejected_no_odometry + fs_stats.scans_rejected_stale}};
    s["odometry"] = {{"received", fs_stats.odometry_received},
                     {"jumps_corrected", fs_stats.odometry_jumps_corrected},
                     {"rejected", fs_stats.odometry_rejected_out_of_order +
                                      fs_stats.odometry_rejected_nonfinite +
                                      fs_stats.odometry_rejected_implausible},
                     {"rejected_implausible", fs_stats.odometry_rejected_implausible}};
    const StageTimes& t = slam.times;
    s["time_s"] = {{"imaging", t.imaging_s},
                   {"features", t.features_s},
                   {"matching", t.matching_s},
                   {"optimization", t.optimization_s},
                   {"total", run.processing_s}};
    const OptimizeResult& opt = slam.last_optimization;
    s["optimization"] = {{"converged", opt.converged},
                         {"termination", opt.termination},
                         {"iterations", opt.iterations},
                         {"final_cost", opt.final_cost}};
    s["map"] = {{"resolution_m", grid.resolution_m},
                {"rows", grid.rows},
                {"cols", grid.cols},
                {"blocks", global.num_blocks()},
                {"memory_mib", static_cast<double>(global.memory_bytes()) / 1048576.0}};
    if (result.ate.num_poses > 0) {
      s["ate"] = AteJson(result.ate);
      s["odometry_ate"] = AteJson(result.odometry_ate);
    }

    // report.html (built from the staged files, so it shows exactly what was written).
    RunReport report;
    report.title = "uwbsar map: " + run.input;
    report.summary = {{"log duration", Fixed(run.log_duration_s, 1) + " s"},
                      {"processing time",
                       Fixed(run.processing_s, 2) + " s (real-time factor " + Fixed(rtf, 1) + ")"},
                      {"path length", Fixed(s["path_length_m"].get<double>(), 2) + " m"},
                      {"keyframes", std::to_string(slam.tiles.size())},
                      {"loops accepted / candidates",
                       std::to_string(accepted) + " / " + std::to_string(slam.loops.size())},
                      {"scans imaged / received", std::to_string(fs_stats.scans_imaged) + " / " +
                                                      std::to_string(fs_stats.scans_received)},
                      {"peak memory", Fixed(PeakMemoryMiB(), 0) + " MiB"}};
    if (result.ate.num_poses > 0) {
      report.summary.push_back({"ATE RMSE (SLAM)", Fixed(result.ate.rmse_m * 100, 2) + " cm"});
      report.summary.push_back(
          {"ATE RMSE (odometry)", Fixed(result.odometry_ate.rmse_m * 100, 2) + " cm"});
    }
    report.images.push_back(
        {"SAR map with the optimised trajectory (white), odometry (grey) and "
         "accepted loops (cyan)",
         ReadFileBytes(staged("map.png"))});
    auto points = [](const std::vector<std::pair<TimestampNs, Pose2>>& traj) {
      std::vector<Point2> out;
      for (std::size_t i = 0; i < traj.size(); i += 5)
        out.push_back({traj[i].second.x_m, traj[i].second.y_m});
      return out;
    };
    if (!run.ground_truth.empty()) {
      std::vector<std::pair<TimestampNs, Pose2>> gt;
      for (const auto& g : run.ground_truth) gt.push_back({g.stamp_ns, g.T_world_robot});
      report.trajectories.push_back({"ground truth", "#222222", points(gt)});
    }
    report.trajectories.push_back({"odometry", "#e76f51", points(odometry)});
    report.trajectories.push_back({"SLAM", "#264653", points(trajectory)});
    for (const LoopRecord& l : slam.loops) {
      if (!l.accepted()) continue;
      const Pose2& a = poses.at(l.match_id);
      const Pose2& b = poses.at(l.query_id);
      report.loop_segments.push_back({{a.x_m, a.y_m}, {b.x_m, b.y_m}});
    }
    ReportTable timing{"Time per stage", {"stage", "seconds", "share"}, {}};
    for (const auto& [name, secs] :
         std::vector<std::pair<std::string, double>>{{"imaging", t.imaging_s},
                                                     {"features", t.features_s},
                                                     {"matching", t.matching_s},
                                                     {"optimization", t.optimization_s}}) {
      timing.rows.push_back(
          {name, Fixed(secs, 3),
           Fixed(run.processing_s > 0 ? 100 * secs / run.processing_s : 0, 1) + " %"});
    }
    report.tables.push_back(timing);
    ReportTable loops{"Loop candidates",
                      {"query", "match", "AKAZE good", "ORB good", "x (m)", "y (m)", "yaw (deg)",
                       "validator", "backend", "reason"},
                      {}};
    for (const LoopRecord& l : slam.loops) {
      const Pose2& T = l.validation.constraint.T_ij;
      const bool v = l.validation.accepted;
      loops.rows.push_back(
          {std::to_string(l.query_id), std::to_string(l.match_id),
           std::to_string(l.akaze.good_matches), std::to_string(l.orb.good_matches),
           v ? Fixed(T.x_m, 3) : "", v ? Fixed(T.y_m, 3) : "",
           v ? Fixed(T.yaw_rad * 180 / M_PI, 2) : "", v ? "accepted" : "rejected",
           v ? (l.rejected_by_backend ? "rejected" : "accepted") : "", l.validation.reason});
    }
    report.tables.push_back(loops);
    WriteTextAtomic(staged("report.html"), RenderReportHtml(report));
    if (exact_from != nullptr) {
      for (const std::string& f : WriteExactMap(*exact_from, stage.string())) {
        names.push_back(fs::path(f).filename().string());
      }
    }
    if (extra_outputs_) {
      for (const std::string& name : extra_outputs_(stage.string())) names.push_back(name);
    }
    WriteTextAtomic(staged("summary.json"), s.dump(2) + "\n");

    // Commit: drop a previous run's summary first, then the outputs this run does not
    // write (a committed folder holds one run's files), then rename, the summary last.
    RemoveOutput(fs::path(out_dir) / "summary.json");
    for (const std::string& name : AllMapOutputNames()) {
      if (std::find(names.begin(), names.end(), name) == names.end()) {
        RemoveOutput(fs::path(out_dir) / name);
      }
    }
    names.push_back("summary.json");
    for (const std::string& name : names) {
      const fs::path target = fs::path(out_dir) / name;
      std::error_code ec;
      fs::rename(stage / name, target, ec);
      if (ec) throw std::runtime_error(target.string() + ": cannot commit: " + ec.message());
      result.files.push_back(target.string());
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
  const StripImage exact = RenderScans(
      scans, slam.sensors(), grid, config.imaging.mode == "coherent", config.imaging.num_threads,
      [&](const ImagedScan& s) { return corrected[&s - scans.data()]; });
  const std::string base = out_dir + "/map_exact";
  WriteFloatTiff(base + "_float.tif", exact.image);
  WriteTextAtomic(base + "_grid.yaml",
                  GridYaml(grid, "map_exact_float.tif and map_exact.png", "map_exact_float.tif"));
  WriteImageAtomic(base + ".png",
                   Colorize(Enhance8U(exact.image, config.enhance), config.enhance.colormap));
  return {base + "_float.tif", base + "_grid.yaml", base + ".png"};
}

}  // namespace uwbsar::tools
