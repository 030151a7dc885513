// PoseGraph's line landmarks (see backend/pose_graph.h and backend/line_landmark.h): straight
// walls whose observations tie every keyframe along a corridor to one line.
#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <cmath>
#include <set>
#include <string>

#include "backend/line_observation_cost.h"
#include "backend/pose_graph.h"
#include "backend/pose_graph_solver.h"
#include "core/errors.h"

namespace uwbsar {
namespace {

bool Finite(const Line2& l) { return std::isfinite(l.normal_rad) && std::isfinite(l.offset_m); }

std::string ObservationName(const LineObservation& o) {
  return "observation of landmark " + std::to_string(o.landmark_id) + " by node " +
         std::to_string(o.node_id);
}

}  // namespace

void PoseGraph::AddLandmark(int id, const Line2& line_world, bool fixed) {
  if (!Finite(line_world)) {
    throw InputError("pose graph: landmark " + std::to_string(id) + " has a non-finite line");
  }
  std::lock_guard<std::mutex> lock(data_mutex_);
  // The solver frame is set by the first node: a landmark needs it to exist.
  if (estimates_.empty()) {
    throw InputError("pose graph: landmark " + std::to_string(id) + " added before any node");
  }
  if (landmarks_.count(id)) {
    throw InputError("pose graph: landmark " + std::to_string(id) + " already exists");
  }
  landmarks_[id] = line_world;
  if (fixed) fixed_landmarks_.insert(id);
  pending_landmarks_.push_back({id, line_world});
}

int PoseGraph::AddLineObservation(const LineObservation& observation) {
  const std::string name = ObservationName(observation);
  if (!Finite(observation.line_node) || !std::isfinite(observation.reference_node.x_m) ||
      !std::isfinite(observation.reference_node.y_m)) {
    throw InputError("pose graph: " + name + " is not finite");
  }
  if (!(observation.offset_std_m > 0.0) || !(observation.normal_std_rad > 0.0)) {
    throw InputError("pose graph: " + name + " needs standard deviations > 0");
  }
  std::lock_guard<std::mutex> lock(data_mutex_);
  if (!estimates_.count(observation.node_id)) {
    throw InputError("pose graph: " + name + " refers to an unknown node");
  }
  if (!landmarks_.count(observation.landmark_id)) {
    throw InputError("pose graph: " + name + " refers to an unknown landmark");
  }
  const int index = static_cast<int>(observations_.size());
  observations_.push_back(observation);
  LineObservationReport report;
  report.index = index;
  report.landmark_id = observation.landmark_id;
  report.node_id = observation.node_id;
  observation_reports_.push_back(report);
  observation_removed_.push_back(false);
  pending_observations_.push_back(index);
  return index;
}

void PoseGraph::InsertPendingLandmarks(const std::vector<std::pair<int, Line2>>& landmarks,
                                       const std::vector<int>& observation_indices,
                                       const std::vector<LineObservation>& observations) {
  for (const auto& [id, line_world] : landmarks) {
    auto landmark = std::make_unique<SolverLandmark>();
    // In the solver frame (the world moved by solver_origin_): n . (p_s + o) = d_w.
    const double a = line_world.normal_rad;
    landmark->x = {a, line_world.offset_m -
                          (std::cos(a) * solver_origin_.x_m + std::sin(a) * solver_origin_.y_m)};
    problem_->AddParameterBlock(landmark->x.data(), 2);
    landmark->fixed = fixed_landmarks_.count(id) > 0;
    if (landmark->fixed) problem_->SetParameterBlockConstant(landmark->x.data());
    solver_landmarks_[id] = std::move(landmark);
  }
  for (std::size_t k = 0; k < observation_indices.size(); ++k) {
    auto so = std::make_unique<SolverObservation>();
    so->index = observation_indices[k];
    so->observation = observations[k];
    so->node = solver_nodes_.at(so->observation.node_id).get();
    so->landmark = solver_landmarks_.at(so->observation.landmark_id).get();
    so->loss = std::make_unique<ceres::LossFunctionWrapper>(MakeRobustLoss(config_),
                                                            ceres::TAKE_OWNERSHIP);
    so->residual =
        problem_->AddResidualBlock(LineObservationCost::Create(so->observation), so->loss.get(),
                                   so->node->x.data(), so->landmark->x.data());
    solver_observations_.push_back(std::move(so));
  }
  // A new landmark starts where its first observation puts it, seen from that node's pose as
  // inserted (a new node may have been re-seeded onto the corrected trajectory above).
  std::set<int> added;
  for (const auto& [id, line_world] : landmarks) added.insert(id);
  ReseedLandmarks(&added);
  for (const auto& [id, line_world] : landmarks) AddRightAngleCandidates(id);
}

bool PoseGraph::UpdateObservationStatus() {
  bool changed = false;
  for (auto& so : solver_observations_) {
    so->chi2 = so->Chi2();
    if (config_.max_rejection_rounds == 0) continue;
    const bool reject = !(so->chi2 <= config_.loop_rejection_chi2);
    if (reject != so->rejected) {
      so->rejected = reject;
      changed = true;
    }
  }
  return changed;
}

void PoseGraph::SetObservationLosses() {
  for (auto& so : solver_observations_) {
    if (so->rejected) {
      so->loss->Reset(new ceres::ScaledLoss(nullptr, 0.0, ceres::TAKE_OWNERSHIP),
                      ceres::TAKE_OWNERSHIP);
    } else {
      so->loss->Reset(MakeRobustLoss(config_), ceres::TAKE_OWNERSHIP);
    }
  }
}

void PoseGraph::ReseedLandmarks(const std::set<int>* only) {
  std::set<int> seeded;
  for (const auto& so : solver_observations_) {
    const int id = so->observation.landmark_id;
    if (so->rejected || so->landmark->fixed || seeded.count(id) ||
        (only != nullptr && !only->count(id))) {
      continue;
    }
    seeded.insert(id);
    const Pose2 T_solver_node{so->node->x[0], so->node->x[1], so->node->x[2]};
    const Line2 before{so->landmark->x[0], so->landmark->x[1]};
    const Line2 line = Facing(LineToWorld(T_solver_node, so->observation.line_node), before);
    so->landmark->x = {line.normal_rad, line.offset_m};
  }
}

double PoseGraph::ObservationChi2Sum() const {
  double sum = 0.0;
  for (const auto& so : solver_observations_) {
    if (!so->rejected) sum += so->Chi2();
  }
  return sum;
}

std::vector<std::array<double, 2>> PoseGraph::LandmarkStates() const {
  std::vector<std::array<double, 2>> states;
  states.reserve(solver_landmarks_.size());
  for (const auto& [id, landmark] : solver_landmarks_) states.push_back(landmark->x);
  return states;
}

void PoseGraph::RestoreLandmarkStates(const std::vector<std::array<double, 2>>& states) {
  std::size_t k = 0;
  for (auto& [id, landmark] : solver_landmarks_) landmark->x = states[k++];
}

void PoseGraph::PublishLandmarks() {
  for (auto& [id, landmark] : solver_landmarks_) {
    const double a = NormalizeAngle(landmark->x[0]);
    landmark->x[0] = a;
    landmarks_[id] = {
        a, landmark->x[1] + std::cos(a) * solver_origin_.x_m + std::sin(a) * solver_origin_.y_m};
  }
  for (const auto& so : solver_observations_) {
    LineObservationReport& r = observation_reports_[static_cast<std::size_t>(so->index)];
    r.chi2 = so->chi2;
    r.rejected = so->rejected;
  }
}

std::map<int, Line2> PoseGraph::GetLandmarks() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return landmarks_;
}

std::vector<LineObservation> PoseGraph::LineObservations() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  std::vector<LineObservation> out;
  for (std::size_t i = 0; i < observations_.size(); ++i) {
    if (!observation_removed_[i]) out.push_back(observations_[i]);
  }
  return out;
}

std::vector<LineObservationReport> PoseGraph::LineObservationReports() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  std::vector<LineObservationReport> out;
  for (std::size_t i = 0; i < observation_reports_.size(); ++i) {
    if (!observation_removed_[i]) out.push_back(observation_reports_[i]);
  }
  return out;
}

}  // namespace uwbsar
