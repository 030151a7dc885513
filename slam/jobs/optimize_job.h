// The job behind `uwbsar optimize`: a g2o pose graph file solved by the backend (robust
// loss, loop rejection, support gate; backend.* configuration), and the optimised graph,
// trajectory and picture written when the solution is one (backend/g2o_io.h,
// backend/graph_plot.h). The command line prints what it returns.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "backend/pose_graph.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

struct OptimizeJobOptions {
  std::string input;    ///< the g2o file (VERTEX_SE2, EDGE_SE2, FIX)
  std::string out_g2o;  ///< the optimised graph (g2o); empty: not written
  std::string out_tum;  ///< the optimised trajectory (TUM, time = vertex id); empty: not written
  std::string out_png;  ///< a picture of the optimised graph; empty: not written
  bool skip_bad_lines = false;  ///< skip (and report) bad lines instead of failing
  bool drop_rejected = false;   ///< leave rejected loops out of out_g2o
};

struct OptimizeJobResult {
  OptimizeResult result;
  std::vector<std::string> skipped_lines;  ///< the bad lines skipped (skip_bad_lines)
  /// Why the solution was not written (not converged, cost or poses not finite, or
  /// degenerate: more than half the loops rejected; such a result would look like a map);
  /// empty when the outputs were written.
  std::string failure;
};

/// Checks the output paths (InputError before any work), reads `options.input` (InputError
/// naming the file and line), calls `on_skipped_line` (optional) with each skipped line as
/// soon as the file is read, solves once with config.backend, then writes the outputs
/// unless the solution failed (see OptimizeJobResult::failure: nothing is written then).
OptimizeJobResult RunOptimizeJob(
    const Config& config, const OptimizeJobOptions& options,
    const std::function<void(const std::string&)>& on_skipped_line = nullptr);

}  // namespace uwbsar::slam
