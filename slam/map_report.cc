#include "slam/map_report.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace uwbsar::slam {
namespace {

/// The key figures at the top of the page.
std::vector<std::pair<std::string, std::string>> ReportSummary(const MapState& run,
                                                               const MapOutputs& outputs) {
  const SlamSnapshot& slam = run.slam;
  const FrontendStats& fs_stats = slam.frontend_stats;
  const double rtf = run.processing_s > 0 ? run.log_duration_s / run.processing_s : 0.0;
  const LoopCounts counts = CountLoops(slam);
  std::vector<std::pair<std::string, std::string>> summary = {
      {"log duration", Fixed(run.log_duration_s, 1) + " s"},
      {"processing time",
       Fixed(run.processing_s, 2) + " s (real-time factor " + Fixed(rtf, 1) + ")"},
      {"path length", Fixed(outputs.summary["path_length_m"].get<double>(), 2) + " m"},
      {"keyframes", std::to_string(slam.tiles.size())},
      {"loops accepted / candidates",
       std::to_string(counts.accepted) + " / " + std::to_string(slam.loops.size())},
      {"scans imaged / received",
       std::to_string(fs_stats.scans_imaged) + " / " + std::to_string(fs_stats.scans_received)},
      {"peak memory", Fixed(PeakMemoryMiB(), 0) + " MiB"}};
  if (outputs.ate.num_poses > 0) {
    summary.push_back({"ATE RMSE (SLAM)", Fixed(outputs.ate.rmse_m * 100, 2) + " cm"});
    summary.push_back({"ATE RMSE (odometry)", Fixed(outputs.odometry_ate.rmse_m * 100, 2) + " cm"});
  }
  return summary;
}

/// Every fifth pose of `traj` as a plot point.
std::vector<Point2> PlotPoints(const StampedPoses& traj) {
  std::vector<Point2> out;
  for (std::size_t i = 0; i < traj.size(); i += 5) {
    out.push_back({traj[i].second.x_m, traj[i].second.y_m});
  }
  return out;
}

ReportTable TimingTable(const MapState& run) {
  const StageTimes& t = run.slam.times;
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
  return timing;
}

ReportTable LoopTable(const SlamSnapshot& slam) {
  const std::vector<DetectorKind> detectors = slam.LoopDetectors();
  ReportTable loops{"Loop candidates", {"query", "match"}, {}};
  for (DetectorKind d : detectors) loops.header.push_back(std::string(DetectorName(d)) + " good");
  for (const char* c : {"x (m)", "y (m)", "yaw (deg)", "validator", "backend", "reason"})
    loops.header.push_back(c);
  for (const LoopRecord& l : slam.loops) {
    const Pose2& T = l.validation.constraint.T_ij;
    const bool v = l.validation.accepted;
    std::vector<std::string> row = {std::to_string(l.query_id), std::to_string(l.match_id)};
    for (DetectorKind d : detectors) row.push_back(std::to_string(l.Match(d).good_matches));
    for (std::string cell :
         {v ? Fixed(T.x_m, 3) : "", v ? Fixed(T.y_m, 3) : "",
          v ? Fixed(T.yaw_rad * 180 / M_PI, 2) : "", std::string(v ? "accepted" : "rejected"),
          std::string(v ? (l.rejected_by_backend ? "rejected" : "accepted") : ""),
          l.validation.reason}) {
      row.push_back(std::move(cell));
    }
    loops.rows.push_back(std::move(row));
  }
  return loops;
}

}  // namespace

std::string Fixed(double v, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << v;
  return out.str();
}

LoopCounts CountLoops(const SlamSnapshot& slam) {
  LoopCounts counts;
  for (const LoopRecord& l : slam.loops) {
    counts.validated += l.validation.accepted;
    counts.accepted += l.accepted();
    counts.backend_rejected += l.validation.accepted && l.rejected_by_backend;
  }
  return counts;
}

RunReport BuildMapReport(const MapState& run, const MapOutputs& outputs,
                         const MapTrajectories& trajectories, const std::string& map_png) {
  const SlamSnapshot& slam = run.slam;
  RunReport report;
  report.title = "uwbsar map: " + run.input;
  report.summary = ReportSummary(run, outputs);
  report.images.push_back(
      {"SAR map with the optimised trajectory (white), odometry (grey) and "
       "accepted loops (cyan)",
       map_png});
  if (!run.ground_truth.empty()) {
    report.trajectories.push_back(
        {"ground truth", "#222222", PlotPoints(trajectories.ground_truth)});
  }
  report.trajectories.push_back({"odometry", "#e76f51", PlotPoints(trajectories.odometry)});
  report.trajectories.push_back({"SLAM", "#264653", PlotPoints(trajectories.slam)});
  for (const LoopRecord& l : slam.loops) {
    if (!l.accepted()) continue;
    const Pose2& a = slam.poses.at(l.match_id);
    const Pose2& b = slam.poses.at(l.query_id);
    report.loop_segments.push_back({{a.x_m, a.y_m}, {b.x_m, b.y_m}});
  }
  report.tables.push_back(TimingTable(run));
  report.tables.push_back(LoopTable(slam));
  return report;
}

}  // namespace uwbsar::slam
