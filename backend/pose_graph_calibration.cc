// PoseGraph's odometry calibration: a new node's estimate on the corrected odometry
// (AddOdometryNode), the calibration blocks, and the trial solve of held-back loops (see
// backend/pose_graph.h, steps 4b and the calibration paragraph).
#include <ceres/problem.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "backend/odometry_calibration.h"
#include "backend/pose_graph.h"
#include "backend/pose_graph_solver.h"

namespace uwbsar {

Pose2 PoseGraph::AddOdometryNode(int from_id, int to_id, const Pose2& T_from_to, int trajectory,
                                 double path_m, double turn_rad) {
  const Pose2 step = config_.odometry_calibration && trajectory >= 0
                         ? CorrectedOdometryStep(config_.CalibrationMean(), T_from_to,
                                                 TravelOf(T_from_to, path_m, turn_rad))
                         : T_from_to;
  const Pose2 estimate = GetPose(from_id) * step;
  AddNode(to_id, estimate, /*reseed_from_odometry=*/false);
  AddOdometryEdge(from_id, to_id, T_from_to, trajectory, path_m, turn_rad);
  return estimate;
}

PoseGraph::CalibrationBlock* PoseGraph::CalibrationFor(int trajectory) {
  auto it = calibrations_.find(trajectory);
  if (it != calibrations_.end()) return it->second.get();
  auto block = std::make_unique<CalibrationBlock>();
  double* x = block->x.data();
  problem_->AddParameterBlock(x, 3);
  const Eigen::Vector3d sigma(config_.calibration_scale_sigma,
                              config_.calibration_heading_drift_sigma_rad_per_m,
                              config_.calibration_rotation_sigma);
  const OdometryCalibration mean = config_.CalibrationMean();
  block->x = mean;  // the base's own calibration until loops free the block
  auto* prior = new OdometryCalibrationPrior(mean, sigma);
  block->prior = prior;
  problem_->AddResidualBlock(prior, nullptr, x);
  // Five sigmas bound the search: the prior is weak, and a calibration beyond that would
  // explain a loop by odometry no base has.
  for (int i = 0; i < 3; ++i) {
    problem_->SetParameterLowerBound(x, i, mean[i] - 5.0 * sigma[i]);
    problem_->SetParameterUpperBound(x, i, mean[i] + 5.0 * sigma[i]);
  }
  problem_->SetParameterBlockConstant(x);
  CalibrationBlock* out = block.get();
  calibrations_[trajectory] = std::move(block);
  return out;
}

void PoseGraph::UpdateCalibrationFreedom() {
  if (calibrations_.empty()) return;
  // Only an accepted loop frees a trajectory's block. A loop ties the heading across the turns
  // between its ends, so it observes the turns' scale together with the drift; wall edges see
  // the drift on straight stretches but never the turns. Freed by wall edges alone, the block
  // corrected the drift while the turns' error stayed at its prior, and where the two cancel
  // over a lap the path moved away from the truth (office ring, one lap: drift 0.0007 rad/m,
  // ATE 9.93 cm of odometry -> 12.84 cm; 10.42 cm held), and the scale and turns' scale, which
  // nothing observed, wandered off their prior (test/backend/wall_edge_test.cc: ATE 1.50 ->
  // 2.58 cm). Once a loop has freed the block, the wall edges refine the drift as well.
  std::map<int, bool> constrained;
  for (const auto& se : solver_edges_) {
    if (se->edge.kind != EdgeKind::kLoop || !se->loss || se->rejected) continue;
    for (const int id : {se->edge.from_id, se->edge.to_id}) {
      auto it = node_trajectory_.find(id);
      if (it != node_trajectory_.end()) constrained[it->second] = true;
    }
  }
  for (auto& [trajectory, block] : calibrations_) {
    const bool free = constrained.count(trajectory) > 0;
    if (free == block->free) continue;
    block->free = free;
    if (free) {
      problem_->SetParameterBlockVariable(block->x.data());
    } else {
      block->x = block->prior->mean();  // nothing observes it: back to the prior
      problem_->SetParameterBlockConstant(block->x.data());
    }
  }
}

double PoseGraph::TotalChi2() const {
  double sum = 0.0;
  for (const auto& se : solver_edges_) {
    if (!se->rejected) sum += se->Chi2();
  }
  for (const auto& [trajectory, block] : calibrations_) sum += block->prior->Chi2(block->x);
  return sum + ObservationChi2Sum();
}

void PoseGraph::TrialSolveHeldBackLoops(OptimizeResult* result) {
  if (config_.max_trial_solves <= 0 || config_.min_loop_support <= 0) return;
  // Each trial is a solve of the whole graph: the most plausible few per call, so that a
  // graph full of held-back false loops (M3500 + 100) costs a few solves, not one per loop.
  std::vector<std::pair<double, SolverEdge*>> candidates;
  for (auto& se : solver_edges_) {
    if (se->loss && se->held_back && !se->trialled) candidates.push_back({se->Chi2(), se.get()});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  if (candidates.size() > static_cast<std::size_t>(config_.max_trial_solves)) {
    candidates.resize(static_cast<std::size_t>(config_.max_trial_solves));
  }
  for (auto& [chi2_alone, trial] : candidates) {
    trial->trialled = true;
    // The map as solved without the loop, to restore on refusal.
    std::vector<std::array<double, 3>> nodes;
    nodes.reserve(solver_nodes_.size());
    for (const auto& [id, node] : solver_nodes_) nodes.push_back(node->x);
    std::vector<OdometryCalibration> calibrations;
    for (const auto& [trajectory, block] : calibrations_) calibrations.push_back(block->x);
    std::vector<bool> rejected;
    for (const auto& se : solver_edges_) rejected.push_back(se->rejected);
    const std::vector<std::array<double, 2>> landmarks = LandmarkStates();
    std::vector<bool> observations_rejected;
    for (const auto& so : solver_observations_) observations_rejected.push_back(so->rejected);
    const double chi2_before = TotalChi2();
    // On refusal the map solved before stands, and so does its solve's convergence report.
    const bool converged_before = result->converged;
    const std::string termination_before = result->termination;

    trial->held_back = false;
    trial->rejected = false;
    SetLoopLosses(false);
    RunSolve(result);
    bool consistent = trial->Chi2() <= config_.loop_rejection_chi2 &&
                      TotalChi2() - chi2_before <= config_.trial_loop_chi2;
    for (const auto& se : solver_edges_) {
      if (!consistent) break;
      const double chi2 = se->Chi2();
      if (se->loss && !se->rejected) consistent = chi2 <= config_.loop_rejection_chi2;
      if (!se->loss && config_.max_odometry_chi2 > 0)
        consistent = chi2 <= config_.max_odometry_chi2;
    }
    if (consistent) {
      trial->trial_accepted = true;
      continue;
    }
    trial->held_back = true;
    result->converged = converged_before;
    result->termination = termination_before;
    std::size_t k = 0;
    for (auto& [id, node] : solver_nodes_) node->x = nodes[k++];
    k = 0;
    for (auto& [trajectory, block] : calibrations_) block->x = calibrations[k++];
    for (std::size_t i = 0; i < solver_edges_.size(); ++i) solver_edges_[i]->rejected = rejected[i];
    RestoreLandmarkStates(landmarks);
    for (std::size_t i = 0; i < solver_observations_.size(); ++i)
      solver_observations_[i]->rejected = observations_rejected[i];
    UpdateCalibrationFreedom();
    SetLoopLosses(false);
  }
}

}  // namespace uwbsar
