#include "slam/outputs/session_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "backend/g2o_io.h"
#include "backend/global_map.h"
#include "backend/occupancy_io.h"
#include "imaging/enhance.h"
#include "imaging/image_io.h"
#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/outputs/map_figure.h"
#include "slam/outputs/map_report.h"
#include "slam/outputs/navigation_map.h"
#include "slam/outputs/output_folder.h"
#include "slam/outputs/report_html.h"
#include "slam/outputs/results_timeline.h"
#include "slam/outputs/session_files.h"
#include "slam/outputs/session_mosaic.h"
#include "slam/outputs/session_report.h"
#include "slam/outputs/summary_json.h"
#include "slam/session/session_file.h"
#include "slam/session/session_merge.h"
#include "slam/slam_snapshot.h"

namespace uwbsar::slam {
namespace {

void Pair(const std::vector<std::pair<TimestampNs, Pose2>>& est,
          const std::vector<OdometrySample>& ref, std::vector<Pose2>* e, std::vector<Pose2>* g) {
  std::vector<OdometrySample> sorted = ref;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.stamp_ns < b.stamp_ns; });
  const TimestampNs max_dt = SecondsToNs(0.01);
  for (const auto& [t, p] : est) {
    auto it =
        std::lower_bound(sorted.begin(), sorted.end(), t,
                         [](const OdometrySample& s, TimestampNs x) { return s.stamp_ns < x; });
    const OdometrySample* best = nullptr;
    TimestampNs best_dt = max_dt + 1;
    for (auto c : {it, it == sorted.begin() ? it : it - 1}) {
      if (c == sorted.end()) continue;
      const TimestampNs dt = std::llabs(c->stamp_ns - t);
      if (dt < best_dt) best_dt = dt, best = &*c;
    }
    if (best == nullptr) continue;
    e->push_back(p);
    g->push_back(best->T_world_robot);
  }
}

/// Output paths in `dir`, each recorded in `files` (in the order written) as it is handed out.
struct OutputPaths {
  std::string dir;
  std::vector<std::string>* files;
  std::string operator()(const std::string& name) const {
    files->push_back(dir + "/" + name);
    return dir + "/" + name;
  }
};

cv::Point Pixel(const ImageGrid& grid, const Pose2& p) {
  return cv::Point(static_cast<int>(std::lround(grid.XToCol(p.x_m))),
                   static_cast<int>(std::lround(grid.YToRow(p.y_m))));
}

/// Run `id` (the n-th): its trajectory drawn on `png` in FigurePalette::Run(n) and into
/// `report` (the plot and the run's own section), trajectory_<id>.tum written, ATE against
/// its ground truth if any. Returns the run's entry of summary.json.
nlohmann::json WriteRun(const SessionData& session, const Config& config, int id, std::size_t n,
                        const ImageGrid& grid,
                        const std::map<int, std::vector<OdometrySample>>& ground_truth,
                        const OutputPaths& path, cv::Mat* png, RunReport* report) {
  const auto traj = CorrectedTrajectory(session, id);
  const FigureColour& colour = FigurePalette::Run(n);
  for (std::size_t i = 1; i < traj.size(); ++i) {
    cv::line(*png, Pixel(grid, traj[i - 1].second), Pixel(grid, traj[i].second), colour.bgr, 2,
             cv::LINE_AA);
  }
  std::vector<std::pair<double, Pose2>> tum;
  std::vector<Point2> points;
  for (std::size_t i = 0; i < traj.size(); ++i) {
    tum.push_back({NsToSeconds(traj[i].first), traj[i].second});
    if (i % 5 == 0 || i + 1 == traj.size())
      points.push_back({traj[i].second.x_m, traj[i].second.y_m});
  }
  const std::string name = "trajectory_" + std::to_string(id) + ".tum";
  WriteTum(path(name), tum);
  std::string input;
  for (const SessionTrajectory& t : session.trajectories)
    if (t.id == id) input = t.input;
  int kept = 0;
  for (const SessionKeyframe& k : session.keyframes) kept += k.trajectory == id;
  nlohmann::json rj = {{"id", id},
                       {"input", input},
                       {"keyframes", KeyframesMade(session, id)},
                       {"keyframes_kept", kept},
                       {"tum", name}};
  report->trajectories.push_back({"run " + std::to_string(id), colour.css, points});
  AteResult ate;
  auto gt = ground_truth.find(id);
  if (gt != ground_truth.end()) {
    ate = TrajectoryError(traj, gt->second);
    rj["ate"] = AteJson(ate);
    report->summary.push_back({"ATE RMSE run " + std::to_string(id) + " (own alignment)",
                               Fixed(ate.rmse_m * 100, 2) + " cm"});
  }
  report->sections.push_back(SessionRunSection(session, config, id, ate));
  return rj;
}

/// summary.json's `loops` over every loop record of the map, as a single run's, and
/// `between_runs`: the accepted ones whose ends are keyframes of two runs.
nlohmann::json LoopsJson(const SessionData& session) {
  int validated = 0, accepted = 0, between = 0;
  for (const SessionLoop& l : session.loops) {
    validated += l.validated;
    accepted += l.accepted;
    between +=
        l.accepted && RunOfKeyframe(session, l.query_id) != RunOfKeyframe(session, l.match_id);
  }
  return {{"candidates", session.loops.size()},
          {"validated", validated},
          {"accepted", accepted},
          {"rejected_by_backend", validated - accepted},
          {"between_runs", between}};
}

/// summary.json's `map`: the mosaic's grid and the blocks of GlobalMap's lattice its keyframes
/// reach, as a single run's sparse canvas would hold them.
nlohmann::json MapJson(const SessionData& session, const Config& config, const ImageGrid& grid) {
  const GlobalMap lattice(config.slam.map_resolution_m);
  GlobalMap::BlockSet blocks;
  for (const SessionKeyframe& k : session.keyframes) {
    const GlobalMap::BlockSet reached = lattice.TileBlocks(k.detected_grid, k.T_map_anchor).Keys();
    blocks.insert(reached.begin(), reached.end());
  }
  const std::size_t block_px = static_cast<std::size_t>(lattice.block_px());
  return MapExtentJson(grid, blocks.size(),
                       blocks.size() * 2u * block_px * block_px * sizeof(float));
}

}  // namespace

std::vector<std::pair<TimestampNs, Pose2>> CorrectedTrajectory(const SessionData& session,
                                                               int trajectory) {
  // The run's kept keyframes and the ones the map retired (anchors), in time order.
  std::vector<TrajectoryAnchor> run;
  for (const SessionKeyframe& k : session.keyframes) {
    if (k.trajectory == trajectory)
      run.push_back({k.id, k.stamp_ns, k.T_odom_anchor, k.T_map_anchor});
  }
  if (!session.anchors.empty()) {
    const std::map<int, Pose2> poses = session.Poses();
    for (const SessionAnchor& a : session.anchors) {
      if (a.trajectory != trajectory) continue;
      if (const std::optional<Pose2> p = a.MapPose(poses))
        run.push_back({a.id, a.stamp_ns, a.T_odom_anchor, *p});
    }
  }
  run = MergeAnchors(std::move(run), {});
  std::vector<std::pair<TimestampNs, Pose2>> out;
  for (const SessionOdometry& o : session.odometry) {
    if (o.trajectory != trajectory) continue;
    out.push_back({o.stamp_ns, CorrectionAt(run, o.stamp_ns) * o.T_odom_robot});
  }
  return out;
}

nlohmann::json MergeReportJson(const MergeReport& r) {
  nlohmann::json j = {
      {"connected", r.connected},       {"keyframe_pairs_matched", r.candidates},
      {"validated", r.validated},       {"dropped_before_placement", r.dropped},
      {"loop_edges", r.loop_edges},     {"loop_edges_rejected", r.loop_edges_rejected},
      {"keyframes_retired", r.retired}, {"walls_reused", r.walls_reused}};
  if (r.connected) {
    j["connect_keyframe_id"] = r.connect_keyframe_id;
    j["connect_path_m"] = r.connect_path_m;
    j["placement"] = {{"x_m", r.T_mapA_mapB.x_m},
                      {"y_m", r.T_mapA_mapB.y_m},
                      {"yaw_deg", r.T_mapA_mapB.yaw_rad * 180.0 / M_PI}};
  } else {
    j["reason"] = r.reason;
  }
  return j;
}

AteResult CommonFrameError(const SessionData& session,
                           const std::map<int, std::vector<OdometrySample>>& ground_truth) {
  std::vector<Pose2> est, ref;
  for (const auto& [id, gt] : ground_truth) Pair(CorrectedTrajectory(session, id), gt, &est, &ref);
  if (est.size() < 2) return AteResult{};
  return ComputeAte(est, ref);
}

SessionOutputs WriteSessionOutputs(const SessionData& session, const Config& config,
                                   const std::string& out_dir,
                                   const std::map<int, std::vector<OdometrySample>>& ground_truth,
                                   const nlohmann::json& extra, const std::string& title,
                                   const std::vector<ReportTable>& timing) {
  EnsureDirectory(out_dir);
  SessionOutputs result;
  const OutputPaths path{out_dir, &result.files};
  const std::map<int, Pose2> poses = session.Poses();
  ImageGrid grid;
  cv::Mat observed;
  const cv::Mat map = RenderSessionMosaic(session, config, &grid, &observed);
  WriteFloatTiff(path("map_float.tif"), map);
  WriteTextAtomic(path("map_grid.yaml"),
                  GridYaml(grid, "map_float.tif and map.png", "map_float.tif", "map"));

  // map.png: the mosaic, each run's corrected trajectory in its colour, accepted loops above.
  const cv::Mat raster = ScaledMapImage(map, observed, config.enhance.colormap);
  cv::Mat png = raster.clone();
  RunReport report;
  report.title = title;
  const std::vector<int> runs = session.TrajectoryIds();
  nlohmann::json runs_json = nlohmann::json::array();
  for (std::size_t n = 0; n < runs.size(); ++n) {
    runs_json.push_back(
        WriteRun(session, config, runs[n], n, grid, ground_truth, path, &png, &report));
  }
  report.loop_segments = SessionLoopSegments(session);
  for (const auto& [a, b] : report.loop_segments) {
    cv::line(png, Pixel(grid, {a.x_m, a.y_m, 0.0}), Pixel(grid, {b.x_m, b.y_m, 0.0}),
             FigurePalette::kLoop.bgr, 1, cv::LINE_AA);
  }
  WriteImageAtomic(path("map.png"), png);
  for (const std::string& name : WriteJoinedRunFiles(session, config, runs, ground_truth, out_dir))
    result.files.push_back(out_dir + "/" + name);
  const OccupancyGrid navigation = SessionNavigationGrid(session, config);
  WriteOccupancyGrid(path("map.yaml"), "map.pgm", navigation);
  result.files.push_back(out_dir + "/map.pgm");
  if (config.slam.results_mcap) {
    WriteSessionResultsMcap(path(kResultsMcapName), session, config, navigation,
                            {map, observed, grid}, ground_truth);
  }
  std::vector<PoseGraphEdge> edges;
  std::vector<int> fixed;
  for (const SessionEdge& e : session.edges) edges.push_back(e.edge);
  for (const SessionKeyframe& k : session.keyframes)
    if (k.fixed) fixed.push_back(k.id);
  WriteTextAtomic(path("graph.g2o"), G2oText(poses, edges, fixed));
  WriteSession(path(kSessionFileName), session, config.session.lossless_tiles);

  // A single run's keys (docs/formats.md): `extra` holds what the command did (CommandWork),
  // the rest describes the whole map.
  nlohmann::json& s = result.summary;
  s = extra;
  s["keyframes"] = session.keyframes.size();
  double path_m = 0.0;
  for (int run : runs) {
    double run_m = 0.0;
    for (const SessionOdometry& o : session.odometry)
      if (o.trajectory == run) run_m = std::max(run_m, o.path_m);
    path_m += run_m;
  }
  s["path_length_m"] = path_m;
  s["loops"] = LoopsJson(session);
  s["runs"] = runs_json;
  s["odometry_calibration"] = OdometryCalibrationJson(config.backend);
  s["map"] = MapJson(session, config, grid);
  // As a plain map's summary: the newest run's ATE (and its odometry's) at the top.
  if (!runs_json.empty() && runs_json.back().contains("ate")) {
    s["ate"] = runs_json.back()["ate"];
    const int newest = runs.back();
    s["odometry_ate"] =
        AteJson(TrajectoryError(PlacedOdometry(session, newest), ground_truth.at(newest)));
  }
  if (ground_truth.size() >= 2) {
    const AteResult common = CommonFrameError(session, ground_truth);
    s["ate_common"] = AteJson(common);
    report.summary.push_back(
        {"ATE RMSE, all runs in one frame", Fixed(common.rmse_m * 100, 2) + " cm"});
  }
  // The loop counts as summary.json and the command's output name them.
  std::vector<std::pair<std::string, std::string>> head = {
      {"runs", std::to_string(runs.size())},
      {"keyframes", std::to_string(session.keyframes.size())},
      {"loops accepted", s["loops"]["accepted"].dump()},
      {"loops accepted between runs", s["loops"]["between_runs"].dump()}};
  if (extra.contains("merge")) {
    head.push_back(
        {"loops between the runs found by the join", extra["merge"]["loop_edges"].dump()});
  }
  report.summary.insert(report.summary.begin(), head.begin(), head.end());
  report.images.push_back(
      {std::string("All runs in the map frame, each in its colour. ") + kMapFigureCaption,
       EncodePng(SessionFigure(session, config, raster, grid))});
  report.tables = timing;
  if (report.tables.empty()) {
    report.tables.push_back({"Time", {"what", "seconds"}, {}, "No timings were recorded."});
  }
  report.tables.back().note +=
      (report.tables.back().note.empty() ? "" : " ") +
      std::string(
          "Runs joined by earlier commands were timed there: their own report.html "
          "holds their stage times.");
  report.tables.push_back(SessionLoopTable(session));
  WriteTextAtomic(path("report.html"), RenderReportHtml(report));
  WriteTextAtomic(path("summary.json"), s.dump(2) + "\n");
  return result;
}

SessionOutputs CommitSessionOutputs(MapOutputStage* stage, const SessionData& session,
                                    const Config& config,
                                    const std::map<int, std::vector<OdometrySample>>& ground_truth,
                                    const nlohmann::json& extra, const std::string& title,
                                    const std::vector<ReportTable>& timing) {
  SessionOutputs out;
  out.files = stage->CommitWritten([&](const std::string& dir) {
    out = WriteSessionOutputs(session, config, dir, ground_truth, extra, title, timing);
    std::vector<std::string> names;
    for (const std::string& f : out.files) {
      names.push_back(std::filesystem::path(f).filename().string());
    }
    return names;
  });
  return out;
}

}  // namespace uwbsar::slam
