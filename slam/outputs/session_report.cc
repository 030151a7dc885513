#include "slam/outputs/session_report.h"

#include <algorithm>
#include <cmath>

#include "slam/outputs/map_figure.h"
#include "slam/outputs/map_report.h"
#include "slam/outputs/session_files.h"
#include "slam/outputs/session_mosaic.h"
#include "slam/outputs/session_outputs.h"

namespace uwbsar::slam {
ReportTable SessionLoopTable(const SessionData& session) {
  std::vector<DetectorKind> detectors;
  for (const SessionLoop& l : session.loops) {
    for (const auto& [d, n] : l.good_matches) {
      if (std::find(detectors.begin(), detectors.end(), d) == detectors.end()) {
        detectors.push_back(d);
      }
    }
  }
  ReportTable table{"Loop candidates", {"query", "match", "query run", "match run"}, {}, ""};
  for (DetectorKind d : detectors) table.header.push_back(std::string(DetectorName(d)) + " good");
  for (const char* c : {"x (m)", "y (m)", "yaw (deg)", "validator", "backend", "chi2", "reason"})
    table.header.push_back(c);
  for (const SessionLoop& l : session.loops) {
    const bool v = l.validated;
    std::vector<std::string> row = {std::to_string(l.query_id), std::to_string(l.match_id),
                                    std::to_string(RunOfKeyframe(session, l.query_id)),
                                    std::to_string(RunOfKeyframe(session, l.match_id))};
    for (DetectorKind d : detectors) {
      const auto it = l.good_matches.find(d);
      row.push_back(it == l.good_matches.end() ? "" : std::to_string(it->second));
    }
    for (std::string cell :
         {v ? Fixed(l.T_ij.x_m, 3) : "", v ? Fixed(l.T_ij.y_m, 3) : "",
          v ? Fixed(l.T_ij.yaw_rad * 180 / M_PI, 2) : "", std::string(v ? "accepted" : "rejected"),
          std::string(v ? (l.accepted ? "accepted" : "rejected") : ""), v ? Fixed(l.chi2, 3) : "",
          l.reason}) {
      row.push_back(std::move(cell));
    }
    table.rows.push_back(std::move(row));
  }
  if (table.rows.empty()) table.note = "No loop candidates were recorded in this session.";
  return table;
}

std::vector<std::pair<Point2, Point2>> SessionLoopSegments(const SessionData& session, int run) {
  std::vector<std::pair<Point2, Point2>> out;
  for (const SessionLoop& l : session.loops) {
    const SessionKeyframe* a = session.Find(l.match_id);
    const SessionKeyframe* b = session.Find(l.query_id);
    if (!l.accepted || a == nullptr || b == nullptr) continue;
    if (run >= 0 && (a->trajectory != run || b->trajectory != run)) continue;
    out.push_back(
        {{a->T_map_anchor.x_m, a->T_map_anchor.y_m}, {b->T_map_anchor.x_m, b->T_map_anchor.y_m}});
  }
  return out;
}

cv::Mat SessionFigure(const SessionData& session, const Config& config, const cv::Mat& raster,
                      const ImageGrid& grid) {
  MapFigure figure;
  figure.map_bgr = raster;
  figure.grid = grid;
  figure.frame = "map";
  figure.colormap = config.enhance.colormap;
  const std::vector<int> runs = session.TrajectoryIds();
  for (std::size_t n = 0; n < runs.size(); ++n) {
    figure.paths.push_back({"run " + std::to_string(runs[n]), FigurePalette::Run(n),
                            PlotPoints(CorrectedTrajectory(session, runs[n]), 1)});
  }
  figure.loops = SessionLoopSegments(session);
  return RenderMapFigure(figure);
}

RunReport SessionRunSection(const SessionData& session, const Config& config, int run,
                            const AteResult& ate) {
  SessionData own;  // the run's keyframes alone: the map its own report showed
  own.config_yaml = session.config_yaml;
  own.source = session.source;
  std::string input;
  for (const SessionTrajectory& t : session.trajectories) {
    if (t.id == run) own.trajectories.push_back(t), input = t.input;
  }
  for (const SessionKeyframe& k : session.keyframes) {
    if (k.trajectory == run) own.keyframes.push_back(k);
  }
  const auto corrected = CorrectedTrajectory(session, run);
  const auto odometry = PlacedOdometry(session, run);
  double path_m = 0.0;
  for (const SessionOdometry& o : session.odometry) {
    if (o.trajectory == run) path_m = std::max(path_m, o.path_m);
  }
  RunReport section;
  section.title = "Run " + std::to_string(run) + ": " + input;
  section.summary = {{"input", input},
                     {"keyframes", std::to_string(KeyframesMade(session, run)) + " (" +
                                       std::to_string(own.keyframes.size()) + " kept in the map)"},
                     {"path length", Fixed(path_m, 2) + " m"}};
  if (ate.num_poses > 0) {
    section.summary.push_back({"ATE RMSE (own alignment)", Fixed(ate.rmse_m * 100, 2) + " cm"});
  }
  section.loop_segments = SessionLoopSegments(session, run);
  if (!own.keyframes.empty()) {
    ImageGrid grid;
    cv::Mat observed;
    const cv::Mat map = RenderSessionMosaic(own, config, &grid, &observed);
    MapFigure figure;
    figure.map_bgr = ScaledMapImage(map, observed, config.enhance.colormap);
    figure.grid = grid;
    figure.frame = "map";
    figure.colormap = config.enhance.colormap;
    figure.paths.push_back({"odometry (placed at its first keyframe)", FigurePalette::kOdometry,
                            PlotPoints(odometry, 1)});
    figure.paths.push_back({"SLAM", FigurePalette::kSlam, PlotPoints(corrected, 1)});
    figure.loops = section.loop_segments;
    figure.loop_label = "accepted loop within the run";
    section.images.push_back({"Run " + std::to_string(run) + ": the map of its own keyframes (" +
                                  kMapFigureCaption + ")",
                              EncodePng(RenderMapFigure(figure))});
  }
  section.trajectories.push_back(
      {"odometry", FigurePalette::kOdometry.css, PlotPoints(odometry, 5)});
  section.trajectories.push_back({"SLAM", FigurePalette::kSlam.css, PlotPoints(corrected, 5)});
  return section;
}

}  // namespace uwbsar::slam
