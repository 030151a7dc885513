#include "backend/pose_graph.h"

#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "backend/chordal_init.h"
#include "backend/pose_graph_solver.h"
#include "backend/se2_edge_cost.h"
#include "core/errors.h"

namespace uwbsar {

namespace {

std::string EdgeName(const PoseGraphEdge& e) {
  return std::string(EdgeKindName(e.kind)) + " edge " + std::to_string(e.from_id) + " -> " +
         std::to_string(e.to_id);
}

bool Finite(const Pose2& p) {
  return std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.yaw_rad);
}

}  // namespace

PoseGraph::PoseGraph(const BackendConfig& config) : config_(config) {
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.enable_fast_removal = true;  // RemoveNode
  problem_ = std::make_unique<ceres::Problem>(options);
}

PoseGraph::~PoseGraph() = default;

void PoseGraph::AddNode(int id, const Pose2& T_world_node, bool reseed_from_odometry) {
  if (!Finite(T_world_node)) {
    throw InputError("pose graph: node " + std::to_string(id) + " has a non-finite pose");
  }
  std::lock_guard<std::mutex> lock(data_mutex_);
  if (estimates_.count(id)) {
    throw InputError("pose graph: node " + std::to_string(id) + " already exists");
  }
  estimates_[id] = T_world_node;
  pending_nodes_.push_back({id, T_world_node, reseed_from_odometry});
}

void PoseGraph::FixNode(int id) {
  std::lock_guard<std::mutex> lock(data_mutex_);
  if (!estimates_.count(id)) {
    throw InputError("pose graph: cannot fix unknown node " + std::to_string(id));
  }
  if (std::find(fixed_ids_.begin(), fixed_ids_.end(), id) != fixed_ids_.end()) return;
  fixed_ids_.push_back(id);
  pending_fixed_.push_back(id);
}

int PoseGraph::AddEdge(const PoseGraphEdge& edge) {
  const std::string name = EdgeName(edge);
  if (edge.from_id == edge.to_id)
    throw InputError("pose graph: " + name + " joins a node to itself");
  if (!Finite(edge.T_from_to))
    throw InputError("pose graph: " + name + " has a non-finite measurement");
  if (!SqrtInformation(edge.information)) {
    throw InputError("pose graph: " + name +
                     " has an information matrix that is not symmetric positive definite");
  }
  // Both times or neither; a step never runs backwards (a gyro's bias acts over its duration).
  if (std::isnan(edge.begin_s) != std::isnan(edge.end_s) || std::isinf(edge.begin_s) ||
      std::isinf(edge.end_s) || edge.end_s < edge.begin_s) {
    throw InputError("pose graph: " + name + " has times " + std::to_string(edge.begin_s) + " .. " +
                     std::to_string(edge.end_s) + " s (both finite, end >= begin)");
  }
  std::lock_guard<std::mutex> lock(data_mutex_);
  for (const int id : {edge.from_id, edge.to_id}) {
    if (!estimates_.count(id)) {
      throw InputError("pose graph: " + name + " refers to unknown node " + std::to_string(id));
    }
  }
  const int index = static_cast<int>(edges_.size());
  edges_.push_back(edge);
  EdgeReport report;
  report.index = index;
  report.from_id = edge.from_id;
  report.to_id = edge.to_id;
  report.kind = edge.kind;
  reports_.push_back(report);
  removed_.push_back(false);
  pending_edges_.push_back(index);
  return index;
}

int PoseGraph::AddOdometryEdge(int from_id, int to_id, const Pose2& T_from_to, int trajectory,
                               double path_m, double turn_rad, double begin_s, double end_s) {
  const double d =
      std::max(std::hypot(T_from_to.x_m, T_from_to.y_m), config_.odometry_min_distance_m);
  PoseGraphEdge e;
  e.from_id = from_id;
  e.to_id = to_id;
  e.T_from_to = T_from_to;
  e.kind = EdgeKind::kOdometry;
  e.trajectory = trajectory;
  e.path_m = path_m;
  e.turn_rad = turn_rad;
  e.begin_s = begin_s;
  e.end_s = end_s;
  e.information =
      Eigen::Vector3d(config_.odometry_xy_information / d, config_.odometry_xy_information / d,
                      config_.odometry_yaw_information / d)
          .asDiagonal();
  return AddEdge(e);
}

int PoseGraph::AddLoopEdge(int from_id, int to_id, const Pose2& T_from_to) {
  PoseGraphEdge e;
  e.from_id = from_id;
  e.to_id = to_id;
  e.T_from_to = T_from_to;
  e.kind = EdgeKind::kLoop;
  e.information = Eigen::Vector3d(config_.loop_xy_information, config_.loop_xy_information,
                                  config_.loop_yaw_information)
                      .asDiagonal();
  return AddEdge(e);
}

void PoseGraph::InsertPending(std::vector<PendingNode> nodes, const std::vector<int>& edge_indices,
                              const std::vector<PoseGraphEdge>& edges,
                              const std::vector<int>& fixed) {
  std::unordered_map<int, bool> reseed;  // new nodes that may still be re-seeded
  for (const PendingNode& n : nodes) {
    if (solver_nodes_.empty()) solver_origin_ = {n.guess.x_m, n.guess.y_m};
    auto node = std::make_unique<SolverNode>();
    node->x = {n.guess.x_m - solver_origin_.x_m, n.guess.y_m - solver_origin_.y_m, n.guess.yaw_rad};
    problem_->AddParameterBlock(node->x.data(), 3);
    if (first_node_id_ < 0) {
      first_node_id_ = n.id;
      problem_->SetParameterBlockConstant(node->x.data());
    }
    // A node the caller fixes keeps the pose it was given.
    if (n.reseed && std::find(fixed.begin(), fixed.end(), n.id) == fixed.end()) reseed[n.id] = true;
    solver_nodes_[n.id] = std::move(node);
  }
  if (!fixed.empty()) {
    if (!explicit_gauge_) {
      explicit_gauge_ = true;
      problem_->SetParameterBlockVariable(solver_nodes_.at(first_node_id_)->x.data());
    }
    for (const int id : fixed) problem_->SetParameterBlockConstant(solver_nodes_.at(id)->x.data());
  }
  for (std::size_t k = 0; k < edge_indices.size(); ++k) {
    auto se = std::make_unique<SolverEdge>();
    se->index = edge_indices[k];
    se->edge = edges[k];
    se->sqrt_information = *SqrtInformation(se->edge.information);  // checked in AddEdge
    se->from = solver_nodes_.at(se->edge.from_id).get();
    se->to = solver_nodes_.at(se->edge.to_id).get();
    if (se->edge.kind == EdgeKind::kOdometry && se->edge.trajectory >= 0 &&
        config_.odometry_calibration) {
      se->calibration = CalibrationFor(se->edge.trajectory);
      se->gyro_bias = GyroBiasFor(se->edge);
      se->travel = TravelOf(se->edge.T_from_to, se->edge.path_m, se->edge.turn_rad);
      if (se->gyro_bias != &no_gyro_bias_)
        se->travel.duration_s = se->edge.end_s - se->edge.begin_s;
      node_trajectory_[se->edge.from_id] = se->edge.trajectory;
      node_trajectory_[se->edge.to_id] = se->edge.trajectory;
    }
    if (se->edge.kind == EdgeKind::kOdometry) {
      auto it = reseed.find(se->edge.to_id);
      if (it != reseed.end() && it->second) {
        const Pose2 T_world_from{se->from->x[0], se->from->x[1], se->from->x[2]};
        const Pose2 T_world_to = T_world_from * se->CorrectedMeasurement();
        se->to->x = {T_world_to.x_m, T_world_to.y_m, T_world_to.yaw_rad};
        it->second = false;
      }
    } else if (se->edge.kind != EdgeKind::kMarginal) {  // loops and walls: robust, rejectable
      se->loss = std::make_unique<ceres::LossFunctionWrapper>(nullptr, ceres::TAKE_OWNERSHIP);
    }
    if (se->calibration != nullptr) {
      se->residual = problem_->AddResidualBlock(
          CalibratedOdometryCost::Create(se->edge.T_from_to, se->travel, se->sqrt_information),
          nullptr, se->from->x.data(), se->to->x.data(), se->calibration->x.data(), se->gyro_bias);
    } else {
      se->residual =
          problem_->AddResidualBlock(new Se2EdgeCost(se->edge.T_from_to, se->sqrt_information),
                                     se->loss.get(), se->from->x.data(), se->to->x.data());
    }
    solver_edges_.push_back(std::move(se));
  }
}

void PoseGraph::RunSolve(OptimizeResult* result) {
  UpdateCalibrationFreedom();
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = config_.max_iterations;
  options.function_tolerance = config_.function_tolerance;
  options.num_threads = config_.num_threads;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, problem_.get(), &summary);
  result->iterations += static_cast<int>(summary.iterations.size()) - 1;
  result->solves += 1;
  result->converged = summary.termination_type == ceres::CONVERGENCE;
  result->termination = ceres::TerminationTypeToString(summary.termination_type) +
                        std::string(": ") + summary.message;
}

void PoseGraph::ChordalStart() {
  std::vector<const double*> constant;
  for (const auto& [id, node] : solver_nodes_) {
    if (problem_->IsParameterBlockConstant(node->x.data())) constant.push_back(node->x.data());
  }
  if (constant.size() != 1) return;  // the relaxation holds exactly one node in place
  int anchor_id = -1;
  std::map<int, Pose2> guess;
  for (const auto& [id, node] : solver_nodes_) {
    guess[id] = Pose2{node->x[0], node->x[1], node->x[2]};
    if (node->x.data() == constant[0]) anchor_id = id;
  }
  std::vector<PoseGraphEdge> edges;
  for (const auto& se : solver_edges_) {
    if (!se->held_back) edges.push_back(se->edge);
  }
  for (const auto& [id, pose] : ChordalInitialization(guess, edges, anchor_id)) {
    solver_nodes_.at(id)->x = {pose.x_m, pose.y_m, pose.yaw_rad};  // solver frame in and out
  }
  ReseedLandmarks();  // the walls move with the nodes that see them
}

double PoseGraph::HalfChi2Sum(bool accepted_only) const {
  double sum = 0.0;
  for (const auto& se : solver_edges_) {
    if (accepted_only && se->rejected) continue;
    sum += se->Chi2();
  }
  return 0.5 * (sum + ObservationChi2Sum());
}

OptimizeResult PoseGraph::Optimize() {
  std::lock_guard<std::mutex> solve_lock(solve_mutex_);
  const auto t0 = std::chrono::steady_clock::now();
  TakePending();
  OptimizeResult result;
  result.converged = true;  // nothing to solve is a solved problem
  result.termination = "no edges";
  result.initial_cost = HalfChi2Sum(false);
  ComputeSupport();
  const bool first = !solved_once_;
  if (first && config_.initialization == GraphInitialization::kChordal) ChordalStart();
  solved_once_ = true;
  if (!solver_edges_.empty()) SolveWithLoopHandling(first, &result);
  if (DecideRightAngles()) SolveWithLoopHandling(false, &result);
  for (auto& se : solver_edges_) se->chi2 = se->Chi2();
  for (auto& so : solver_observations_) so->chi2 = so->Chi2();
  result.final_cost = HalfChi2Sum(true);
  PublishSolution(&result);
  result.num_nodes = static_cast<int>(solver_nodes_.size());
  result.num_edges = static_cast<int>(solver_edges_.size());
  result.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

void PoseGraph::TakePending() {
  std::vector<PendingNode> nodes;
  std::vector<int> edge_indices;
  std::vector<PoseGraphEdge> edges;
  std::vector<int> fixed;
  std::vector<std::pair<int, Line2>> landmarks;
  std::vector<int> observation_indices;
  std::vector<LineObservation> observations;
  std::vector<PendingBiasMeasurement> bias_measurements;
  {
    std::lock_guard<std::mutex> lock(data_mutex_);
    bias_measurements.swap(pending_bias_measurements_);
    nodes.swap(pending_nodes_);
    edge_indices.swap(pending_edges_);
    fixed.swap(pending_fixed_);
    landmarks.swap(pending_landmarks_);
    observation_indices.swap(pending_observations_);
    for (const int i : edge_indices) edges.push_back(edges_[static_cast<std::size_t>(i)]);
    for (const int i : observation_indices)
      observations.push_back(observations_[static_cast<std::size_t>(i)]);
  }
  InsertPending(std::move(nodes), edge_indices, edges, fixed);
  InsertPendingLandmarks(landmarks, observation_indices, observations);
  for (const PendingBiasMeasurement& m : bias_measurements) {
    GyroBiasTrackFor(m.trajectory)->AddMeasurement(m.t_s, m.bias_radps, m.sigma_radps);
  }
}

void PoseGraph::SolveWithLoopHandling(bool first, OptimizeResult* result) {
  const bool robust = config_.robust_loss != RobustLoss::kNone;
  bool settled = false;
  if (!first) {
    // Warm update: the current estimate is the map solved without the held-back loops,
    // so they are tested right away; then plain least squares, and the robust rounds
    // only when some loop changes status.
    AdmitConfirmedLoops();
    SetLoopLosses(false);
    RunSolve(result);
    settled = !UpdateLoopStatus();
  }
  if (!settled) {
    RejectionRounds(robust, result);
    if (AdmitConfirmedLoops()) RejectionRounds(robust, result);
    if (robust && config_.final_least_squares &&
        std::any_of(solver_edges_.begin(), solver_edges_.end(),
                    [](const auto& se) { return se->loss && !se->rejected; })) {
      // Plain least squares on the inliers; a loop that only fit under the robust loss
      // is rejected and the inliers re-solved.
      RejectionRounds(false, result);
    }
  }
  TrialSolveHeldBackLoops(result);
  ConsistencyRounds(result);
}

void PoseGraph::PublishSolution(OptimizeResult* result) {
  std::lock_guard<std::mutex> lock(data_mutex_);
  for (auto& [id, node] : solver_nodes_) {
    node->x[2] = NormalizeAngle(node->x[2]);
    estimates_[id] =
        Pose2{node->x[0] + solver_origin_.x_m, node->x[1] + solver_origin_.y_m, node->x[2]};
  }
  for (const auto& [trajectory, block] : calibrations_) calibrations_out_[trajectory] = block->x;
  for (const auto& [trajectory, track] : gyro_bias_tracks_)
    gyro_biases_out_[trajectory] = track->Segments();
  PublishLandmarks();
  for (const auto& se : solver_edges_) {
    EdgeReport& r = reports_[static_cast<std::size_t>(se->index)];
    r.chi2 = se->chi2;
    r.rejected = se->rejected;
    r.support = se->support;
    r.reason = !se->rejected      ? ""
               : se->held_back    ? "unsupported"
               : se->inconsistent ? "inconsistent"
                                  : "chi2";
    if (r.rejected) result->rejected.push_back(r);
    if (r.kind == EdgeKind::kLoop) ++result->num_loops;
  }
}

bool PoseGraph::HasNode(int id) const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return estimates_.count(id) > 0;
}

Pose2 PoseGraph::GetPose(int id) const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return estimates_.at(id);
}

std::map<int, Pose2> PoseGraph::GetPoses() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return estimates_;
}

std::vector<PoseGraphEdge> PoseGraph::Edges() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  std::vector<PoseGraphEdge> out;
  out.reserve(edges_.size());
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    if (!removed_[i]) out.push_back(edges_[i]);
  }
  return out;
}

std::vector<EdgeReport> PoseGraph::EdgeReports() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  std::vector<EdgeReport> out;
  out.reserve(reports_.size());
  for (std::size_t i = 0; i < reports_.size(); ++i) {
    if (!removed_[i]) out.push_back(reports_[i]);
  }
  return out;
}

std::vector<int> PoseGraph::FixedNodes() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return fixed_ids_;
}

std::map<int, std::array<double, 3>> PoseGraph::OdometryCalibrations() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return calibrations_out_;
}

std::map<int, std::vector<std::pair<double, double>>> PoseGraph::GyroBiases() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return gyro_biases_out_;
}

int PoseGraph::NumNodes() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return static_cast<int>(estimates_.size());
}

int PoseGraph::NumEdges() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return static_cast<int>(std::count(removed_.begin(), removed_.end(), false));
}

}  // namespace uwbsar
