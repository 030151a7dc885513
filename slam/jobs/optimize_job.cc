#include "slam/jobs/optimize_job.h"

#include <cmath>

#include "backend/g2o_io.h"
#include "backend/graph_plot.h"
#include "core/shortest_number.h"
#include "imaging/image_io.h"
#include "slam/outputs/map_figure.h"
#include "slam/outputs/output_folder.h"

namespace uwbsar::slam {
namespace {

/// Why the solve must not be written (not converged, cost or poses not finite); empty if
/// it may: such a result would look like a map.
std::string SolveFailure(const OptimizeResult& r, const PoseGraph& graph) {
  std::string failure;
  if (!r.converged) failure = "the solver did not converge: " + r.termination;
  if (failure.empty() && !std::isfinite(r.final_cost)) {
    failure = "the final cost is not finite (" + std::to_string(r.final_cost) + ")";
  }
  for (const auto& [id, pose] : graph.GetPoses()) {
    if (failure.empty() &&
        !(std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.yaw_rad))) {
      failure = "the solution is not finite (vertex " + std::to_string(id) + ")";
    }
  }
  return failure;
}

/// Why the solution is degenerate although it converged: more than half the loops rejected,
/// so the graph keeps the tangle those loops should have closed (MIT-B with the defaults: 11
/// of 20 held back as unsupported). Says which key changes it; empty if usable.
std::string DegenerateSolution(const OptimizeResult& r, const BackendConfig& backend) {
  int rejected = 0, unsupported = 0;
  for (const EdgeReport& e : r.rejected) {
    if (e.kind != EdgeKind::kLoop) continue;
    ++rejected;
    unsupported += e.reason == "unsupported";
  }
  if (r.num_loops == 0 || 2 * rejected <= r.num_loops) return {};
  std::string why = std::to_string(rejected) + " of " + std::to_string(r.num_loops) +
                    " loops rejected, the optimised graph would keep the tangle they close: ";
  if (2 * unsupported >= rejected) {
    why += std::to_string(unsupported) +
           " unsupported (no loop within backend.loop_support_window" +
           " agrees, backend.min_loop_support: " + std::to_string(backend.min_loop_support) +
           "); for a graph whose loops are isolated set backend.min_loop_support: 0 (with "
           "--init chordal for a poor initial guess)";
  } else {
    why += std::to_string(rejected - unsupported) +
           " by their residual (backend.loop_rejection_chi2: " +
           ShortestNumber(backend.loop_rejection_chi2) +
           "); for a poor initial guess try --init chordal (backend.initialization)";
  }
  return why;
}

/// The pose-graph plot framed like the map figures: axes in metres of the graph's frame, a
/// scale bar, a legend of the edge colours, and the first and last poses (by id) marked.
/// Loops are drawn above the chain (backend/graph_plot.h).
cv::Mat GraphFigure(const PoseGraph& graph) {
  const std::map<int, Pose2> poses = graph.GetPoses();
  MapFigure figure;
  figure.map_bgr = PlotPoseGraph(poses, graph.Edges(), graph.EdgeReports(), 1000, &figure.grid);
  figure.frame = "graph";
  figure.colour_bar = false;
  figure.background = cv::Scalar(255, 255, 255);
  if (!poses.empty()) {
    const Pose2& first = poses.begin()->second;
    const Pose2& last = poses.rbegin()->second;
    // The chain is in the raster; the path only marks its first and last pose (by id).
    figure.paths.push_back({"odometry chain",
                            {"black", kGraphOdometryBgr, "#000000"},
                            {{first.x_m, first.y_m}, {last.x_m, last.y_m}},
                            true,
                            false});
  }
  figure.raster_legend = {{"accepted loop", kGraphLoopBgr},
                          {"rejected loop", kGraphRejectedLoopBgr}};
  return RenderMapFigure(figure);
}

void WriteOptimizeOutputs(const OptimizeJobOptions& options, const PoseGraph& graph) {
  if (!options.out_g2o.empty()) WriteG2o(options.out_g2o, graph, options.drop_rejected);
  if (!options.out_tum.empty()) {
    std::vector<std::pair<double, Pose2>> trajectory;
    for (const auto& [id, pose] : graph.GetPoses()) trajectory.push_back({id, pose});
    WriteTum(options.out_tum, trajectory);
  }
  if (!options.out_png.empty()) WriteImageAtomic(options.out_png, GraphFigure(graph));
}

}  // namespace

OptimizeJobResult RunOptimizeJob(const Config& config, const OptimizeJobOptions& options,
                                 const std::function<void(const std::string&)>& on_skipped_line) {
  for (const std::string* out : {&options.out_g2o, &options.out_tum, &options.out_png}) {
    if (!out->empty()) CheckOutputFile(*out);  // before the work
  }
  G2oReadOptions read;
  read.skip_bad_lines = options.skip_bad_lines;
  read.max_file_mb = config.limits.max_input_file_mb;
  const G2oGraph file = ReadG2o(options.input, read);
  if (on_skipped_line) {
    for (const std::string& s : file.skipped) on_skipped_line(s);
  }
  PoseGraph graph(config.backend);
  LoadIntoPoseGraph(file, &graph);
  OptimizeJobResult job;
  job.result = graph.Optimize();
  job.skipped_lines = file.skipped;
  job.failure = SolveFailure(job.result, graph);
  if (job.failure.empty()) job.failure = DegenerateSolution(job.result, config.backend);
  if (job.failure.empty()) WriteOptimizeOutputs(options, graph);
  return job;
}

}  // namespace uwbsar::slam
