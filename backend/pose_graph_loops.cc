// PoseGraph's handling of loop closures between solves (see backend/pose_graph.h, steps 1-4):
// robust or plain losses, chi2 rejection rounds, the neighbour support of loops (held back
// when alone), and the odometry consistency rounds after a solve.
#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <algorithm>
#include <string>
#include <vector>

#include "backend/loop_support.h"
#include "backend/odometry_consistency.h"
#include "backend/pose_graph.h"
#include "backend/pose_graph_solver.h"

namespace uwbsar {
void PoseGraph::SetLoopLosses(bool robust) {
  for (auto& se : solver_edges_) {
    if (!se->loss) continue;
    if (se->rejected) {
      // A zero-weight loss switches the residual off but keeps the problem's structure.
      se->loss->Reset(new ceres::ScaledLoss(nullptr, 0.0, ceres::TAKE_OWNERSHIP),
                      ceres::TAKE_OWNERSHIP);
    } else {
      se->loss->Reset(robust ? MakeRobustLoss(config_) : nullptr, ceres::TAKE_OWNERSHIP);
    }
  }
  SetObservationLosses();  // always robust: a wall may bend or end
}

bool PoseGraph::UpdateLoopStatus() {
  bool changed = false;
  for (auto& se : solver_edges_) {
    se->chi2 = se->Chi2();
    if (!se->loss || se->held_back || se->inconsistent || config_.max_rejection_rounds == 0)
      continue;
    const bool reject = !(se->chi2 <= config_.loop_rejection_chi2);
    if (reject != se->rejected) {
      se->rejected = reject;
      changed = true;
    }
  }
  if (UpdateObservationStatus()) changed = true;
  return changed;
}

void PoseGraph::RejectionRounds(bool robust, OptimizeResult* result) {
  for (int round = 0; round < std::max(1, config_.max_rejection_rounds); ++round) {
    SetLoopLosses(robust);
    RunSolve(result);
    if (!UpdateLoopStatus()) break;
  }
}

bool PoseGraph::AdmitConfirmedLoops() {
  bool admitted = false;
  for (auto& se : solver_edges_) {
    if (se->held_back && se->Chi2() <= config_.unsupported_loop_chi2) {
      se->held_back = false;
      se->rejected = false;
      admitted = true;
    }
  }
  return admitted;
}

void PoseGraph::ComputeSupport() {
  if (config_.min_loop_support <= 0) return;
  std::vector<PoseGraphEdge> edges;
  edges.reserve(solver_edges_.size());
  for (const auto& se : solver_edges_) edges.push_back(se->edge);
  LoopSupportOptions options;
  options.window_nodes = config_.loop_support_window;
  options.max_cycle_chi2 = config_.loop_rejection_chi2;
  const std::vector<int> support = CountLoopSupport(edges, options);
  for (std::size_t i = 0; i < solver_edges_.size(); ++i) {
    SolverEdge& se = *solver_edges_[i];
    se.support = support[i];
    if (!se.loss || se.trial_accepted || se.edge.kind != EdgeKind::kLoop) continue;
    se.held_back = support[i] < config_.min_loop_support;
    if (se.held_back) se.rejected = true;
  }
}

void PoseGraph::ConsistencyRounds(OptimizeResult* result) {
  if (config_.max_odometry_chi2 <= 0) return;
  for (int round = 0; round < std::max(1, config_.max_rejection_rounds); ++round) {
    std::vector<SolvedEdge> solved;
    solved.reserve(solver_edges_.size());
    for (const auto& se : solver_edges_) {
      solved.push_back({&se->edge, se->Chi2(), !se->rejected, se->support});
    }
    const int blamed = LoopToBlame(solved, config_.max_odometry_chi2);
    if (blamed < 0) return;
    SolverEdge& se = *solver_edges_[static_cast<std::size_t>(blamed)];
    se.rejected = true;
    se.inconsistent = true;
    SetLoopLosses(false);
    RunSolve(result);
    UpdateLoopStatus();
  }
}

}  // namespace uwbsar
