// PoseGraph's right-angle priors between line landmarks (BackendConfig::landmark_right_angle_*;
// see backend/pose_graph.h): which pairs of walls are held at a whole number of quarter turns,
// decided once the walls are enclosed by a loop and only in a building whose walls look
// rectilinear.
#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "backend/line_right_angle_cost.h"
#include "backend/pose_graph.h"
#include "backend/pose_graph_solver.h"
#include "backend/rectilinear_frame.h"

namespace uwbsar {

void PoseGraph::AddRightAngleCandidates(int id) {
  const SolverLandmark* a = solver_landmarks_.at(id).get();
  if (config_.landmark_right_angle_std_deg > 0.0 && rectilinear_ != Rectilinear::kNo) {
    const int n = static_cast<int>(landmark_order_.size());
    for (int k = n - 1; k >= 0 && k >= n - config_.landmark_right_angle_pairs; --k) {
      const int other = landmark_order_[static_cast<std::size_t>(k)];
      if (a->fixed && solver_landmarks_.at(other)->fixed) continue;  // nothing to hold
      right_angle_candidates_.push_back({id, other});
    }
  }
  landmark_order_.push_back(id);
}

bool PoseGraph::DecideRightAngles() {
  if (right_angle_candidates_.empty()) return false;
  // The keyframes that see each landmark: the span of their node ids (ids grow along a run) and
  // how many they are.
  struct Seen {
    int first = 0, last = 0, count = 0;
  };
  std::map<int, Seen> seen_by;
  for (const auto& so : solver_observations_) {
    if (so->rejected) continue;
    const int node = so->observation.node_id;
    auto [it, inserted] = seen_by.try_emplace(so->observation.landmark_id, Seen{node, node, 0});
    it->second.first = std::min(it->second.first, node);
    it->second.last = std::max(it->second.last, node);
    ++it->second.count;
  }
  std::vector<std::pair<int, int>> loop_spans;
  for (const auto& se : solver_edges_) {
    if (se->edge.kind != EdgeKind::kLoop || se->rejected) continue;
    loop_spans.push_back(std::minmax(se->edge.from_id, se->edge.to_id));
  }
  auto enclosed = [&](int first, int last) {
    return std::any_of(loop_spans.begin(), loop_spans.end(), [&](const auto& span) {
      return span.first <= first && span.second >= last;
    });
  };
  // Is the building rectilinear? Decided once, from the walls the first loops enclose (at least
  // kMinWalls of them), before any prior squares them: each wall weighs as many keyframes as see
  // it.
  if (rectilinear_ == Rectilinear::kUnknown) {
    std::vector<double> normals, weights;
    for (const auto& [id, seen] : seen_by) {
      if (!enclosed(seen.first, seen.last)) continue;
      normals.push_back(solver_landmarks_.at(id)->x[0]);
      weights.push_back(seen.count);
    }
    constexpr std::size_t kMinWalls = 4;
    if (normals.size() < kMinWalls) return false;
    const double spread_deg = FitRectilinearFrame(normals, weights).rms_rad * 180.0 / M_PI;
    rectilinear_ = spread_deg <= config_.landmark_right_angle_max_spread_deg ? Rectilinear::kYes
                                                                             : Rectilinear::kNo;
    std::lock_guard<std::mutex> lock(data_mutex_);
    building_spread_deg_ = spread_deg;
  }
  if (rectilinear_ == Rectilinear::kNo) {
    right_angle_candidates_.clear();
    return false;
  }
  const double quarter = 0.5 * M_PI;
  const double gate_rad = config_.landmark_right_angle_gate_deg * M_PI / 180.0;
  const double std_rad = config_.landmark_right_angle_std_deg * M_PI / 180.0;
  bool added = false;
  std::vector<std::pair<int, int>> undecided;
  for (const auto& [id_a, id_b] : right_angle_candidates_) {
    const auto a_seen = seen_by.find(id_a);
    const auto b_seen = seen_by.find(id_b);
    if (a_seen == seen_by.end() || b_seen == seen_by.end() ||
        !enclosed(std::min(a_seen->second.first, b_seen->second.first),
                  std::max(a_seen->second.last, b_seen->second.last))) {
      undecided.push_back({id_a, id_b});
      continue;
    }
    // Decided once, on the solution with the enclosing loop: the heading drift and turn scale
    // between the two walls are then solved, and the angle left is the building's.
    SolverLandmark* a = solver_landmarks_.at(id_a).get();
    SolverLandmark* b = solver_landmarks_.at(id_b).get();
    const double d = NormalizeAngle(a->x[0] - b->x[0]);
    const int turns = static_cast<int>(std::lround(d / quarter));
    if (std::abs(d - turns * quarter) > gate_rad) continue;
    right_angle_losses_.emplace_back(MakeRobustLoss(config_));
    problem_->AddResidualBlock(LineRightAngleCost::Create(turns, std_rad),
                               right_angle_losses_.back().get(), a->x.data(), b->x.data());
    added = true;
    std::lock_guard<std::mutex> lock(data_mutex_);
    ++right_angle_priors_;
  }
  right_angle_candidates_.swap(undecided);
  return added;
}

int PoseGraph::RightAnglePriors() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return right_angle_priors_;
}

double PoseGraph::BuildingSpreadDeg() const {
  std::lock_guard<std::mutex> lock(data_mutex_);
  return building_spread_deg_;
}

}  // namespace uwbsar
