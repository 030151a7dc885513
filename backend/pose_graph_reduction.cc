// PoseGraph::RemoveNode (see backend/pose_graph.h): folding a node out of the graph.
//
// The folded edges compose the node's measurements through the hub, which is exact for a node
// on a chain (odometry in, odometry out) and, for a node with loops, drops the correlation of
// the folded edges that share the hub's edge (slightly over-confident, as every star-shaped
// sparsification is; Kretzschmar and Stachniss, IJRR 2012, measure its effect).
#include <ceres/problem.h>

#include <Eigen/LU>
#include <algorithm>
#include <map>
#include <string>

#include "backend/edge_composition.h"
#include "backend/pose_graph.h"
#include "backend/pose_graph_solver.h"
#include "core/errors.h"

namespace uwbsar {
namespace {

Pose2 PoseOf(const std::array<double, 3>& x) { return Pose2{x[0], x[1], x[2]}; }

/// The node's edge as seen from the node: the neighbour, and its measured pose in the node's
/// frame with the covariance of that measurement.
struct NodeEdge {
  int neighbour = 0;
  RelativePose T_node_neighbour;
  double strength = 0.0;  // det of the information: how strongly it ties the two
};

}  // namespace

void PoseGraph::EraseSolverNode(int id) {
  auto node = solver_nodes_.find(id);
  problem_->RemoveParameterBlock(node->second->x.data());  // and its residual blocks
  std::lock_guard<std::mutex> lock(data_mutex_);
  solver_edges_.erase(std::remove_if(solver_edges_.begin(), solver_edges_.end(),
                                     [&](const std::unique_ptr<SolverEdge>& se) {
                                       if (se->edge.from_id != id && se->edge.to_id != id)
                                         return false;
                                       removed_[static_cast<std::size_t>(se->index)] = true;
                                       return true;
                                     }),
                      solver_edges_.end());
  // Its landmark observations leave with it (the landmark keeps the others').
  solver_observations_.erase(
      std::remove_if(solver_observations_.begin(), solver_observations_.end(),
                     [&](const std::unique_ptr<SolverObservation>& so) {
                       if (so->observation.node_id != id) return false;
                       observation_removed_[static_cast<std::size_t>(so->index)] = true;
                       return true;
                     }),
      solver_observations_.end());
  solver_nodes_.erase(node);
  node_trajectory_.erase(id);
  estimates_.erase(id);
}

int PoseGraph::RemoveNode(int id, Pose2* T_hub_node) {
  std::lock_guard<std::mutex> solve_lock(solve_mutex_);
  TakePending();  // edges queued since the last solve are the node's edges too
  auto node = solver_nodes_.find(id);
  if (node == solver_nodes_.end())
    throw InputError("pose graph: cannot remove unknown node " + std::to_string(id));
  const auto is_fixed = [this](int n) {
    return problem_->IsParameterBlockConstant(solver_nodes_.at(n)->x.data());
  };
  const bool fixed = is_fixed(id);
  if (!solved_once_)
    throw InputError("pose graph: cannot remove node " + std::to_string(id) + " before a solve");

  // The node's edges that constrain it, as measurements from the node.
  std::vector<NodeEdge> ties;
  std::vector<SolverEdge*> absorbed;  // marginal edges between two neighbours, merged below
  for (const auto& se : solver_edges_) {
    const bool from = se->edge.from_id == id, to = se->edge.to_id == id;
    if (!from && !to) continue;
    if (se->rejected || se->edge.kind == EdgeKind::kWall) continue;  // dropped with the node
    const Eigen::Matrix3d cov = se->edge.information.inverse();
    // The measurement (a calibrated odometry step as the current calibration corrects it),
    // not the estimate: composed measurements keep the pull the node's edges exerted on its
    // neighbours, so that a chain folds exactly (two springs in series).
    const Pose2 z = se->CorrectedMeasurement();
    const RelativePose m{z, cov};
    NodeEdge tie;
    tie.neighbour = from ? se->edge.to_id : se->edge.from_id;
    tie.T_node_neighbour = from ? m : InvertRelativePose(m);
    tie.strength = se->edge.information.determinant();
    ties.push_back(tie);
  }
  // Parallel edges to one neighbour act as one (informations add at the solution).
  std::map<int, NodeEdge> by_neighbour;
  for (const NodeEdge& t : ties) {
    auto [it, inserted] = by_neighbour.emplace(t.neighbour, t);
    if (inserted) continue;
    it->second.T_node_neighbour =
        FuseRelativePoses(it->second.T_node_neighbour, t.T_node_neighbour);
    it->second.strength = it->second.T_node_neighbour.covariance.inverse().determinant();
  }
  // A fixed node (a frozen saved map) folds into a fixed neighbour: both stay where they are,
  // so the step between them is exact, and what the node's edges said about a free neighbour
  // carries over unchanged.
  int hub = -1;
  double best = -1.0;
  for (const auto& [n, t] : by_neighbour) {
    if (fixed && !is_fixed(n)) continue;
    if (t.strength > best) {
      best = t.strength;
      hub = n;
    }
  }
  if (fixed && hub < 0 && !by_neighbour.empty()) {
    throw InputError("pose graph: cannot remove fixed node " + std::to_string(id) +
                     ": no fixed neighbour to fold it into");
  }
  const Pose2 T_world_node = PoseOf(node->second->x);
  if (hub >= 0 && T_hub_node != nullptr)
    *T_hub_node = Between(PoseOf(solver_nodes_.at(hub)->x), T_world_node);

  std::vector<PoseGraphEdge> folded;
  if (hub >= 0) {
    const RelativePose node_hub =
        fixed ? RelativePose{Between(T_world_node, PoseOf(solver_nodes_.at(hub)->x)),
                             Eigen::Matrix3d::Zero()}
              : by_neighbour.at(hub).T_node_neighbour;
    for (const auto& [n, t] : by_neighbour) {
      if (n == hub) continue;
      // neighbour -> node -> hub.
      RelativePose n_hub = ComposeRelativePoses(InvertRelativePose(t.T_node_neighbour), node_hub);
      // A marginal edge already between n and hub (either way) is merged into this one.
      for (const auto& se : solver_edges_) {
        if (se->edge.kind != EdgeKind::kMarginal) continue;
        const bool same = se->edge.from_id == n && se->edge.to_id == hub;
        const bool reverse = se->edge.from_id == hub && se->edge.to_id == n;
        if (!same && !reverse) continue;
        RelativePose old{se->edge.T_from_to, se->edge.information.inverse()};
        if (reverse) old = InvertRelativePose(old);
        n_hub = FuseRelativePoses(n_hub, old);
        absorbed.push_back(se.get());
      }
      PoseGraphEdge e;
      e.from_id = n;
      e.to_id = hub;
      e.kind = EdgeKind::kMarginal;
      e.T_from_to = n_hub.T_a_b;
      const Eigen::Matrix3d info = n_hub.covariance.inverse();
      e.information = 0.5 * (info + info.transpose());
      folded.push_back(e);
    }
  }
  EraseSolverNode(id);
  if (fixed) {
    std::lock_guard<std::mutex> lock(data_mutex_);
    fixed_ids_.erase(std::remove(fixed_ids_.begin(), fixed_ids_.end(), id), fixed_ids_.end());
  }
  for (SolverEdge* se : absorbed) problem_->RemoveResidualBlock(se->residual);
  {
    std::lock_guard<std::mutex> lock(data_mutex_);
    solver_edges_.erase(std::remove_if(solver_edges_.begin(), solver_edges_.end(),
                                       [&](const std::unique_ptr<SolverEdge>& se) {
                                         if (std::find(absorbed.begin(), absorbed.end(),
                                                       se.get()) == absorbed.end())
                                           return false;
                                         removed_[static_cast<std::size_t>(se->index)] = true;
                                         return true;
                                       }),
                        solver_edges_.end());
  }
  // The folded edges enter the solver now, in the solver frame like every estimate.
  for (PoseGraphEdge& e : folded) AddEdge(e);
  TakePending();
  return hub;
}

}  // namespace uwbsar
