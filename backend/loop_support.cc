#include "backend/loop_support.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <deque>
#include <unordered_map>

namespace uwbsar {
namespace {

/// Adjoint of SE(2) for tangent vectors ordered (x, y, yaw).
Eigen::Matrix3d Adjoint(const Pose2& T) {
  const double c = std::cos(T.yaw_rad), s = std::sin(T.yaw_rad);
  Eigen::Matrix3d ad;
  ad << c, -s, T.y_m,  //
      s, c, -T.x_m,    //
      0.0, 0.0, 1.0;
  return ad;
}

struct Link {
  int to = 0;
  UncertainPose2 T;  // from the node owning the link to `to`
};

struct Reached {
  UncertainPose2 T;  // T_origin_node
  int steps = 0;
};
using Neighbourhood = std::unordered_map<int, Reached>;

}  // namespace

UncertainPose2 EdgeAsUncertainPose(const PoseGraphEdge& edge) {
  // The residual treats (dx, dy, dyaw) as additive noise on the measurement; as a right
  // perturbation, the translation noise is seen from the frame of `to`.
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
  const double c = std::cos(edge.T_from_to.yaw_rad), s = std::sin(edge.T_from_to.yaw_rad);
  rot.topLeftCorner<2, 2>() << c, s, -s, c;  // R^T
  UncertainPose2 u;
  u.T = edge.T_from_to;
  u.covariance = rot * edge.information.inverse() * rot.transpose();
  return u;
}

UncertainPose2 Compose(const UncertainPose2& a_b, const UncertainPose2& b_c) {
  // T_ab exp(xi1) T_bc exp(xi2) = T_ab T_bc exp(Ad(T_bc^-1) xi1) exp(xi2).
  const Eigen::Matrix3d ad = Adjoint(b_c.T.Inverse());
  return {a_b.T * b_c.T, ad * a_b.covariance * ad.transpose() + b_c.covariance};
}

UncertainPose2 Inverse(const UncertainPose2& a_b) {
  // (T exp(xi))^-1 = exp(-xi) T^-1 = T^-1 exp(-Ad(T) xi).
  const Eigen::Matrix3d ad = Adjoint(a_b.T);
  return {a_b.T.Inverse(), ad * a_b.covariance * ad.transpose()};
}

namespace {

/// The odometry chain and the loops of a graph, with the odometry neighbourhoods of nodes
/// (computed once per node and cached) that CountLoopSupport pairs loops through.
class SupportCounter {
 public:
  SupportCounter(const std::vector<PoseGraphEdge>& edges, const LoopSupportOptions& options)
      : edges_(edges), options_(options) {
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const PoseGraphEdge& e = edges[i];
      if (e.kind == EdgeKind::kOdometry) {
        const UncertainPose2 forward = EdgeAsUncertainPose(e);
        chain_[e.from_id].push_back({e.to_id, forward});
        chain_[e.to_id].push_back({e.from_id, Inverse(forward)});
      } else if (e.kind == EdgeKind::kLoop) {  // wall edges neither give nor get support
        loops_at_[e.from_id].push_back(i);
        loops_at_[e.to_id].push_back(i);
      }
    }
  }

  /// Loops (other than loop i) that close a consistent cycle with it.
  int Support(std::size_t i) {
    int support = 0;
    for (const auto& [k, pairing] : Pairings(i)) {
      const UncertainPose2& cycle = pairing.cycle;
      const Eigen::Vector3d xi(cycle.T.x_m, cycle.T.y_m, cycle.T.yaw_rad);
      const Eigen::LDLT<Eigen::Matrix3d> ldlt(cycle.covariance);
      if (ldlt.info() != Eigen::Success) continue;
      if (xi.dot(ldlt.solve(xi)) <= options_.max_cycle_chi2) ++support;
    }
    return support;
  }

 private:
  struct Pairing {
    int steps = 0;
    UncertainPose2 cycle;  ///< a -> b -> d -> c -> a; identity when both loops are right
  };

  /// Nodes within window_nodes odometry steps of `origin`, with T_origin_node (breadth
  /// first).
  const Neighbourhood& Near(int origin) {
    auto it = cache_.find(origin);
    if (it != cache_.end()) return it->second;
    Neighbourhood n;
    n[origin] = Reached{};
    std::deque<std::pair<int, int>> queue{{origin, 0}};
    while (!queue.empty()) {
      const auto [node, depth] = queue.front();
      queue.pop_front();
      if (depth >= options_.window_nodes) continue;
      auto links = chain_.find(node);
      if (links == chain_.end()) continue;
      for (const Link& link : links->second) {
        if (n.count(link.to)) continue;
        n[link.to] = Reached{Compose(n[node].T, link.T), depth + 1};
        queue.push_back({link.to, depth + 1});
      }
    }
    return cache_.emplace(origin, std::move(n)).first->second;
  }

  /// Loop i (a -> b) paired with each other loop c -> d whose ends lie near a and b. Each
  /// other loop is paired once, in the orientation with the shortest odometry links (a
  /// loop whose ends are both near `a` would otherwise also pair the long way).
  std::unordered_map<std::size_t, Pairing> Pairings(std::size_t i) {
    const PoseGraphEdge& l = edges_[i];
    const Neighbourhood& near_a = Near(l.from_id);
    const Neighbourhood& near_b = Near(l.to_id);
    const UncertainPose2 T_ab = EdgeAsUncertainPose(l);
    std::unordered_map<std::size_t, Pairing> best;
    for (const auto& [c, a_c] : near_a) {
      auto at_c = loops_at_.find(c);
      if (at_c == loops_at_.end()) continue;
      for (const std::size_t k : at_c->second) {
        if (k == i) continue;
        const PoseGraphEdge& m = edges_[k];
        // Orient the other loop as c -> d with c near a.
        UncertainPose2 T_cd = EdgeAsUncertainPose(m);
        int d = m.to_id;
        if (m.from_id != c) {
          T_cd = Inverse(T_cd);
          d = m.from_id;
        }
        const auto b_d = near_b.find(d);
        if (b_d == near_b.end()) continue;
        const int steps = a_c.steps + b_d->second.steps;
        auto it = best.find(k);
        if (it != best.end() && it->second.steps <= steps) continue;
        best[k] = {steps,
                   Compose(Compose(Compose(T_ab, b_d->second.T), Inverse(T_cd)), Inverse(a_c.T))};
      }
    }
    return best;
  }

  const std::vector<PoseGraphEdge>& edges_;
  const LoopSupportOptions& options_;
  std::unordered_map<int, std::vector<Link>> chain_;            // odometry links, both ways
  std::unordered_map<int, std::vector<std::size_t>> loops_at_;  // node -> loop edge indices
  std::unordered_map<int, Neighbourhood> cache_;
};

}  // namespace

std::vector<int> CountLoopSupport(const std::vector<PoseGraphEdge>& edges,
                                  const LoopSupportOptions& options) {
  SupportCounter counter(edges, options);
  std::vector<int> support(edges.size(), -1);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (edges[i].kind == EdgeKind::kLoop) support[i] = counter.Support(i);
  }
  return support;
}

}  // namespace uwbsar
