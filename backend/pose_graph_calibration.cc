// PoseGraph's odometry calibration: a new node's estimate on the corrected odometry
// (AddOdometryNode), the calibration blocks, and the trial solve of held-back loops (see
// backend/pose_graph.h, steps 4b and the calibration paragraph).
#include <ceres/manifold.h>
#include <ceres/problem.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "backend/gyro_bias_track.h"
#include "backend/odometry_calibration.h"
#include "backend/pose_graph.h"
#include "backend/pose_graph_solver.h"
#include "core/errors.h"

namespace uwbsar {

bool PoseGraph::UsesGyroBias(int trajectory) const {
  return config_.odometry_calibration && trajectory >= 0 &&
         config_.odometry_model == OdometryModel::kGyro;
}

Pose2 PoseGraph::AddOdometryNode(int from_id, int to_id, const Pose2& T_from_to, int trajectory,
                                 double path_m, double turn_rad, double begin_s, double end_s) {
  Pose2 step = T_from_to;
  if (config_.odometry_calibration && trajectory >= 0) {
    OdometryTravel travel = TravelOf(T_from_to, path_m, turn_rad);
    double bias_radps = 0.0;
    if (UsesGyroBias(trajectory) && std::isfinite(begin_s) && std::isfinite(end_s)) {
      // The bias as last solved (or as the standstills measured it): a new keyframe starts on
      // the corrected heading, not on the raw gyro's.
      travel.duration_s = end_s - begin_s;
      std::lock_guard<std::mutex> lock(data_mutex_);
      auto it = gyro_biases_out_.find(trajectory);
      if (it != gyro_biases_out_.end() && !it->second.empty())
        bias_radps = it->second.back().second;
    }
    step = CorrectedOdometryStep(config_.CalibrationMean(), T_from_to, travel, bias_radps);
  }
  const Pose2 estimate = GetPose(from_id) * step;
  AddNode(to_id, estimate, /*reseed_from_odometry=*/false);
  AddOdometryEdge(from_id, to_id, T_from_to, trajectory, path_m, turn_rad, begin_s, end_s);
  return estimate;
}

void PoseGraph::AddGyroBiasMeasurement(int trajectory, double t_s, double bias_radps,
                                       double sigma_radps) {
  if (!std::isfinite(t_s) || !std::isfinite(bias_radps) || !(sigma_radps > 0) ||
      !std::isfinite(sigma_radps)) {
    throw InputError("pose graph: gyro bias measurement at " + std::to_string(t_s) +
                     " s: " + std::to_string(bias_radps) + " +- " + std::to_string(sigma_radps) +
                     " rad/s (finite, sigma > 0)");
  }
  if (!UsesGyroBias(trajectory)) return;
  std::lock_guard<std::mutex> lock(data_mutex_);
  pending_bias_measurements_.push_back({trajectory, t_s, bias_radps, sigma_radps});
}

GyroBiasTrack* PoseGraph::GyroBiasTrackFor(int trajectory) {
  auto it = gyro_bias_tracks_.find(trajectory);
  if (it == gyro_bias_tracks_.end()) {
    it = gyro_bias_tracks_
             .emplace(trajectory, std::make_unique<GyroBiasTrack>(problem_.get(), config_))
             .first;
  }
  return it->second.get();
}

double* PoseGraph::GyroBiasFor(const PoseGraphEdge& edge) {
  if (!UsesGyroBias(edge.trajectory) || std::isnan(edge.begin_s)) {
    if (!problem_->HasParameterBlock(&no_gyro_bias_)) {
      problem_->AddParameterBlock(&no_gyro_bias_, 1);
      problem_->SetParameterBlockConstant(&no_gyro_bias_);
    }
    return &no_gyro_bias_;
  }
  return GyroBiasTrackFor(edge.trajectory)->BlockAt(0.5 * (edge.begin_s + edge.end_s));
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
  // A gyro base's heading error is its bias (backend/gyro_bias_track.h), never a drift per metre:
  // the two would trade against each other along any path driven at a steady speed.
  if (config_.odometry_model == OdometryModel::kGyro) {
    problem_->SetManifold(x, new ceres::SubsetManifold(3, {kCalibHeadingDrift}));
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
  for (const auto& [trajectory, track] : gyro_bias_tracks_) sum += track->Chi2();
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
    std::vector<std::vector<double>> gyro_biases;
    for (const auto& [trajectory, track] : gyro_bias_tracks_) gyro_biases.push_back(track->State());
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
    k = 0;
    for (auto& [trajectory, track] : gyro_bias_tracks_) track->Restore(gyro_biases[k++]);
    for (std::size_t i = 0; i < solver_edges_.size(); ++i) solver_edges_[i]->rejected = rejected[i];
    RestoreLandmarkStates(landmarks);
    for (std::size_t i = 0; i < solver_observations_.size(); ++i)
      solver_observations_[i]->rejected = observations_rejected[i];
    UpdateCalibrationFreedom();
    SetLoopLosses(false);
  }
}

}  // namespace uwbsar
