#include "slam/outputs/map_report.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <tuple>

#include "slam/outputs/map_figure.h"

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

ReportTable LoopTable(const SlamSnapshot& slam) {
  const std::vector<DetectorKind> detectors = slam.LoopDetectors();
  ReportTable loops{"Loop candidates", {"query", "match"}, {}, ""};
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

std::vector<Point2> PlotPoints(const StampedPoses& traj, std::size_t every) {
  std::vector<Point2> out;
  for (std::size_t i = 0; i < traj.size(); i += every) {
    out.push_back({traj[i].second.x_m, traj[i].second.y_m});
  }
  if (!traj.empty() && (traj.size() - 1) % every != 0) {
    out.push_back({traj.back().second.x_m, traj.back().second.y_m});
  }
  return out;
}

ReportTable StageTimingTable(const StageTimes& t, double wall_s, bool keyframe_thread,
                             const std::string& title) {
  const char* keyframe = keyframe_thread ? "keyframe" : "feeding";
  ReportTable timing{title, {"stage", "thread", "seconds", "% of wall time"}, {}, ""};
  auto share = [&](double secs) { return Fixed(wall_s > 0 ? 100 * secs / wall_s : 0, 1) + " %"; };
  for (const auto& [name, thread, secs] : std::vector<std::tuple<std::string, const char*, double>>{
           {"imaging", "feeding", t.imaging_s},
           {"features", keyframe, t.features_s},
           {"matching", keyframe, t.matching_s},
           {"optimization", keyframe, t.optimization_s}}) {
    timing.rows.push_back({name, thread, Fixed(secs, 3), share(secs)});
  }
  const double sum = t.imaging_s + t.features_s + t.matching_s + t.optimization_s;
  timing.rows.push_back({"sum of the stages", "", Fixed(sum, 3), share(sum)});
  timing.rows.push_back({"wall time (the whole run)", "", Fixed(wall_s, 3), share(wall_s)});
  timing.note =
      keyframe_thread
          ? "The stages overlap: the feeding thread images scans while the keyframe thread "
            "extracts features, matches and optimises, so their seconds may add up to more "
            "than the wall time. Each share is that stage's seconds over the wall time, not a "
            "part of a whole; the wall time also holds reading the log and waiting."
          : "All stages ran on the feeding thread (slam.keyframe_thread: false), one after "
            "another; the wall time also holds reading the log, the shares are of the wall time.";
  return timing;
}

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

std::vector<FigurePath> RunFigurePaths(const MapTrajectories& trajectories, std::size_t every) {
  std::vector<FigurePath> paths;
  FigurePath slam{"SLAM", FigurePalette::kSlam, PlotPoints(trajectories.slam, every)};
  slam.width = 2.0;
  paths.push_back(slam);
  paths.push_back({"odometry", FigurePalette::kOdometry, PlotPoints(trajectories.odometry, every)});
  if (!trajectories.ground_truth.empty()) {
    FigurePath truth{"ground truth", FigurePalette::kGroundTruth,
                     PlotPoints(trajectories.ground_truth, every)};
    truth.dashed = true;
    paths.push_back(truth);
  }
  return paths;
}

std::vector<ReportTrajectory> RunReportTrajectories(const MapTrajectories& trajectories) {
  std::vector<ReportTrajectory> out;
  for (const FigurePath& p : RunFigurePaths(trajectories, 5)) {
    out.push_back({p.label, p.colour.css, p.points, 2.0 * p.width, p.dashed});
  }
  return out;
}

cv::Mat MapReportFigure(const MapState& run, const MapTrajectories& trajectories,
                        const cv::Mat& map_bgr, const ImageGrid& grid) {
  const SlamSnapshot& slam = run.slam;
  MapFigure figure;
  figure.map_bgr = map_bgr;
  figure.grid = grid;
  figure.colormap = slam.config->enhance.colormap;
  figure.paths = RunFigurePaths(trajectories, 1);
  figure.loops = slam.AcceptedLoopSegments();
  return RenderMapFigure(figure);
}

RunReport BuildMapReport(const MapState& run, const MapOutputs& outputs,
                         const MapTrajectories& trajectories, const std::string& figure_png) {
  const SlamSnapshot& slam = run.slam;
  RunReport report;
  report.title = "uwbsar map: " + run.input;
  report.summary = ReportSummary(run, outputs);
  report.images.push_back({kMapFigureCaption, figure_png});
  report.trajectories = RunReportTrajectories(trajectories);
  report.loop_segments = slam.AcceptedLoopSegments();
  report.tables.push_back(
      StageTimingTable(slam.times, run.processing_s, slam.config->slam.keyframe_thread));
  report.tables.push_back(LoopTable(slam));
  return report;
}

}  // namespace uwbsar::slam
