#include "slam/optimize_job.h"

#include <cmath>

#include "backend/g2o_io.h"
#include "backend/graph_plot.h"
#include "imaging/image_io.h"
#include "slam/output_folder.h"

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

void WriteOptimizeOutputs(const OptimizeJobOptions& options, const PoseGraph& graph) {
  if (!options.out_g2o.empty()) WriteG2o(options.out_g2o, graph, options.drop_rejected);
  if (!options.out_tum.empty()) {
    std::vector<std::pair<double, Pose2>> trajectory;
    for (const auto& [id, pose] : graph.GetPoses()) trajectory.push_back({id, pose});
    WriteTum(options.out_tum, trajectory);
  }
  if (!options.out_png.empty()) {
    WriteImageAtomic(options.out_png,
                     PlotPoseGraph(graph.GetPoses(), graph.Edges(), graph.EdgeReports()));
  }
}

}  // namespace

OptimizeJobResult RunOptimizeJob(const Config& config, const OptimizeJobOptions& options,
                                 const std::function<void(const std::string&)>& on_skipped_line) {
  for (const std::string* out : {&options.out_g2o, &options.out_tum, &options.out_png}) {
    if (!out->empty()) CheckOutputFile(*out);  // before the work
  }
  G2oReadOptions read;
  read.skip_bad_lines = options.skip_bad_lines;
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
  if (job.failure.empty()) WriteOptimizeOutputs(options, graph);
  return job;
}

}  // namespace uwbsar::slam
